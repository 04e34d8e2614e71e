#include "bumpshadow/parallel.h"

#include <algorithm>
#include <atomic>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

namespace ffsim::bumpshadow {

void parallel_rows(int rows, int threads, const std::function<void(int)>& body, const Progress& progress) {
  if (threads <= 0) threads = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  threads = std::max(1, std::min(threads, rows));
  std::atomic<int> next{0};
  std::mutex m;
  int done = 0;
  std::exception_ptr error;
  auto worker = [&] {
    for (;;) {
      const int row = next.fetch_add(1);
      if (row >= rows) return;
      try {
        body(row);
      } catch (...) {
        std::lock_guard<std::mutex> lock(m);
        if (!error) error = std::current_exception();
        next.store(rows);
        return;
      }
      std::lock_guard<std::mutex> lock(m);
      ++done;
      if (progress) progress(done, rows);
    }
  };
  if (threads == 1) {
    worker();
  } else {
    std::vector<std::thread> pool;
    for (int t = 0; t < threads; ++t) pool.emplace_back(worker);
    for (auto& t : pool) t.join();
  }
  if (error) std::rethrow_exception(error);
}

}  // namespace ffsim::bumpshadow
