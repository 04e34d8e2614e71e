// A small persistent pool of worker threads (docs/performance.md "Threads"):
// run(n, fn) calls fn(0) .. fn(n − 1), spread over the workers and the calling
// thread, and returns when all have finished. The draw splits the rows of a
// glEnd's polygons into bands, one task each; tasks must touch disjoint data.
#pragma once
#include <condition_variable>
#include <exception>
#include <functional>
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
  // The first exception a task throws is rethrown here (after all tasks ended).
  void run(int n, const std::function<void(int)>& fn);

 private:
  void work();
  void drain();  // take tasks until none is left
  std::vector<std::thread> workers_;
  std::mutex m_;
  std::condition_variable wake_, done_;
  const std::function<void(int)>* fn_ = nullptr;
  int n_ = 0, next_ = 0, running_ = 0;
  unsigned long generation_ = 0;
  bool stop_ = false;
  std::exception_ptr error_;
};

}  // namespace ffsim
