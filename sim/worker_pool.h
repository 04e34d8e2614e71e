// A small persistent pool of worker threads (docs/performance.md "Threads"):
// run(n, fn) calls fn(0) .. fn(n − 1), spread over the workers and the calling
// thread, and returns when all have finished. The draw splits the rows of a
// glEnd's polygons into bands, one task each; tasks must touch disjoint data.
//
// Tasks have a home: participant k of T (0 the caller, 1 .. T − 1 the workers)
// owns the contiguous tasks [k·n/T, (k+1)·n/T) and takes them first, in order;
// one whose own are done takes the others' last remaining task (stealing from
// the back). So when consecutive runs split the same rows the same way (the
// passes over one mesh), a band runs on the same thread pass after pass and its
// framebuffer lines and scratch stay in that core's caches (docs/performance.md
// 19.1), while a late or slow thread still cannot hold the others up. Which thread
// runs a task never changes what it computes (tasks touch disjoint data).
//
// Waiting spins before it sleeps: a worker that has run out of tasks watches for
// the next run for up to kSpin, and the caller watches for the last task to end,
// before blocking on a condition variable. On a virtual machine a sleeping
// thread took about 0.1 ms to wake, the cost of a whole band of a small pass
// (docs/performance.md 19.2); the passes of a multipass frame come a fraction of
// a millisecond apart.
#pragma once
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <exception>
#include <functional>
#include <memory>
#include <mutex>
#include <thread>
#include <vector>

namespace ffsim {

class WorkerPool {
 public:
  explicit WorkerPool(int threads);  // threads − 1 workers (the caller is one more)
  ~WorkerPool();
  WorkerPool(const WorkerPool&) = delete;
  WorkerPool& operator=(const WorkerPool&) = delete;
  int threads() const { return static_cast<int>(workers_.size()) + 1; }
  // A pool of `threads` from the process's idle pools, or a new one; it goes back
  // to them when the last shared_ptr to it is dropped. A Context replayed per
  // frame (ffsim bench, the paper run) then starts no thread per frame
  // (docs/performance.md 20). A borrowed pool has one user at a time.
  static std::shared_ptr<WorkerPool> borrow(int threads);
  // The first exception a task throws is rethrown here (after all tasks ended).
  // on_caller: every task on the calling thread, in order, the workers left idle;
  // what a task computes is the same (a diagnostic of the split work's own cost
  // on one core: Context::set_split_on_caller, docs/performance.md 38).
  void run(int n, const std::function<void(int)>& fn, bool on_caller = false);
  // Tasks of the last run() that ran on a participant other than their home's.
  int stolen() const { return stolen_; }
  // How long the caller of the last run() waited after its own last task for
  // the other participants' (0 on one participant or on_caller).
  std::chrono::steady_clock::duration last_wait() const { return last_wait_; }
  // How long after the last run() began another participant took its first
  // task: a late start (a worker asleep, or its vCPU taken) against the tail
  // of the last task (last_wait). If no other participant took a task, the time
  // until the caller had run them all. 0 on one participant or on_caller.
  std::chrono::steady_clock::duration last_start() const { return last_start_; }

 private:
  static constexpr std::chrono::microseconds kSpin{2000};
  void work(int self);
  void drain(int self);  // take tasks until none is left
  int take(int self);    // the next task for participant `self`, or −1 (under m_)
  std::vector<std::thread> workers_;
  std::mutex m_;
  std::condition_variable wake_, done_;
  const std::function<void(int)>* fn_ = nullptr;
  std::vector<int> lo_, hi_;  // per participant: its tasks not yet taken, [lo, hi)
  int left_ = 0, running_ = 0, stolen_ = 0;
  std::chrono::steady_clock::duration last_wait_{0};
  std::chrono::steady_clock::duration last_start_{0};
  std::chrono::steady_clock::time_point run_start_{}, first_other_{};  // (under m_)
  bool other_took_ = false;                                              // (under m_)
  std::atomic<int> unfinished_{0};  // tasks of this run not yet ended (read while spinning)
  std::atomic<unsigned long> generation_{0};
  std::atomic<bool> stop_{false};
  std::exception_ptr error_;
};

}  // namespace ffsim
