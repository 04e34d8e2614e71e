#include "sim/worker_pool.h"

#include <algorithm>

#if defined(__x86_64__) || defined(__i386__)
#include <immintrin.h>
#endif

namespace ffsim {

namespace {

// A hint to the core that this is a spin-wait loop (x86 PAUSE, ARM YIELD).
inline void cpu_relax() {
#if defined(__x86_64__) || defined(__i386__)
  _mm_pause();
#elif defined(__aarch64__) || defined(__arm__)
  asm volatile("yield");
#endif
}

// Spins until done() holds or `limit` has passed; true if done() held. Every 64
// checks it yields the CPU, so a thread that has no core of its own (more
// threads than cores, or a loaded machine) lets the one it waits for run.
template <class Done>
bool spin_until(Done done, std::chrono::microseconds limit) {
  const auto end = std::chrono::steady_clock::now() + limit;
  for (;;) {
    for (int i = 0; i < 64; ++i) {
      if (done()) return true;
      cpu_relax();
    }
    if (std::chrono::steady_clock::now() >= end) return done();
    std::this_thread::yield();
  }
}

// The idle pools, owned here until borrowed. Each borrowed pool's deleter holds
// the registry, so a pool dropped during static destruction still finds it.
struct IdlePools {
  static constexpr std::size_t kKeep = 4;  // idle pools kept; the oldest goes first
  std::mutex m;
  std::vector<std::unique_ptr<WorkerPool>> idle;
  IdlePools() { idle.reserve(kKeep); }  // a return never allocates (deleters must not throw)
};

std::shared_ptr<IdlePools> idle_pools() {
  static const std::shared_ptr<IdlePools> pools = std::make_shared<IdlePools>();
  return pools;
}

}  // namespace

std::shared_ptr<WorkerPool> WorkerPool::borrow(int threads) {
  std::shared_ptr<IdlePools> reg = idle_pools();
  std::unique_ptr<WorkerPool> pool;
  {
    std::lock_guard<std::mutex> lock(reg->m);
    // The most recently returned pool of that size (its threads ran last).
    for (auto it = reg->idle.rbegin(); it != reg->idle.rend(); ++it)
      if ((*it)->threads() == std::max(threads, 1)) {
        pool = std::move(*it);
        reg->idle.erase(std::next(it).base());
        break;
      }
  }
  if (!pool) pool = std::make_unique<WorkerPool>(threads);
  return std::shared_ptr<WorkerPool>(pool.release(), [reg](WorkerPool* p) {
    std::unique_ptr<WorkerPool> oldest;  // evicted when full; joined after the unlock
    std::lock_guard<std::mutex> lock(reg->m);
    if (reg->idle.size() >= IdlePools::kKeep) {
      oldest = std::move(reg->idle.front());
      reg->idle.erase(reg->idle.begin());
    }
    reg->idle.emplace_back(p);
  });
}

WorkerPool::WorkerPool(int threads) {
  const auto t = static_cast<std::size_t>(threads < 1 ? 1 : threads);
  lo_.assign(t, 0);
  hi_.assign(t, 0);
  for (int i = 1; i < threads; ++i) workers_.emplace_back([this, i] { work(i); });
}

WorkerPool::~WorkerPool() {
  {
    std::lock_guard<std::mutex> lock(m_);
    stop_ = true;
  }
  wake_.notify_all();
  for (std::thread& t : workers_) t.join();
}

int WorkerPool::take(int self) {
  const auto s = static_cast<std::size_t>(self);
  if (lo_[s] < hi_[s]) return lo_[s]++;  // its own, front first
  // Steal the last task of the participant with the most left (ties: the lowest index).
  std::size_t from = s;
  int most = 0;
  for (std::size_t k = 0; k < lo_.size(); ++k)
    if (hi_[k] - lo_[k] > most) most = hi_[k] - lo_[k], from = k;
  if (most == 0) return -1;
  ++stolen_;
  return --hi_[from];
}

void WorkerPool::drain(int self) {
  std::unique_lock<std::mutex> lock(m_);
  for (int i; left_ > 0 && (i = take(self)) >= 0;) {
    if (self != 0 && !other_took_) {  // (last_start)
      other_took_ = true;
      first_other_ = std::chrono::steady_clock::now();
    }
    --left_;
    ++running_;
    lock.unlock();
    try {
      (*fn_)(i);
    } catch (...) {
      std::lock_guard<std::mutex> g(m_);
      if (!error_) error_ = std::current_exception();
    }
    lock.lock();
    --running_;
    unfinished_.fetch_sub(1, std::memory_order_release);
  }
  if (left_ == 0 && running_ == 0) done_.notify_all();
}

void WorkerPool::work(int self) {
  unsigned long seen = 0;
  for (;;) {
    spin_until([&] { return stop_.load(std::memory_order_relaxed) || generation_.load(std::memory_order_relaxed) != seen; },
               kSpin);
    {
      std::unique_lock<std::mutex> lock(m_);
      wake_.wait(lock, [&] { return stop_ || generation_ != seen; });
      if (stop_) return;
      seen = generation_;
    }
    drain(self);
  }
}

void WorkerPool::run(int n, const std::function<void(int)>& fn, bool on_caller) {
  last_wait_ = std::chrono::steady_clock::duration{0};
  last_start_ = std::chrono::steady_clock::duration{0};
  stolen_ = 0;
  if (n <= 0) return;
  if (on_caller) {  // (the workers are not woken: they stay as they are)
    std::exception_ptr err;
    for (int i = 0; i < n; ++i) {
      try {
        fn(i);
      } catch (...) {
        if (!err) err = std::current_exception();
      }
    }
    if (err) std::rethrow_exception(err);
    return;
  }
  {
    std::lock_guard<std::mutex> lock(m_);
    fn_ = &fn;
    const auto t = static_cast<long long>(lo_.size());
    for (std::size_t k = 0; k < lo_.size(); ++k) {  // participant k's home: [k·n/T, (k+1)·n/T)
      lo_[k] = static_cast<int>(static_cast<long long>(n) * static_cast<long long>(k) / t);
      hi_[k] = static_cast<int>(static_cast<long long>(n) * static_cast<long long>(k + 1) / t);
    }
    left_ = n;
    running_ = 0;
    unfinished_ = n;
    error_ = nullptr;
    other_took_ = false;
    run_start_ = std::chrono::steady_clock::now();
    ++generation_;
  }
  wake_.notify_all();
  drain(0);
  const auto own_done = std::chrono::steady_clock::now();
  spin_until([&] { return unfinished_.load(std::memory_order_acquire) == 0; }, kSpin);
  std::exception_ptr err;
  {
    std::unique_lock<std::mutex> lock(m_);
    done_.wait(lock, [&] { return left_ == 0 && running_ == 0; });
    fn_ = nullptr;
    err = error_;
    if (threads() > 1) last_start_ = (other_took_ ? first_other_ : own_done) - run_start_;
  }
  if (threads() > 1) last_wait_ = std::chrono::steady_clock::now() - own_done;
  if (err) std::rethrow_exception(err);
}

}  // namespace ffsim
