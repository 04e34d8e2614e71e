// `ffsim bench --perf` (issue 10): per-stage throughput in million fragments per
// second on one core, whole-trace frames per second over sizes and threads, each
// beside the memory-bandwidth floor of the pass; a table, CSV and a plot under
// docs/results/.
#pragma once
#include <iosfwd>
#include <string>
#include <vector>

namespace ffsim::bench {

// args: the arguments after `ffsim bench --perf`. Returns the exit code.
int run_perf(const std::vector<std::string>& args, std::ostream& out, std::ostream& err);

std::string perf_usage();

// Amdahl's bound on the speed-up of `threads` threads: a frame that takes
// `one_thread_s` on one thread, of which `serial_s` (measured on `threads`
// threads: the calling thread's time outside the pool's runs) cannot be split,
// and the rest splits perfectly: one_thread_s / (serial_s + (one_thread_s -
// serial_s) / threads). A serial part longer than the one-thread frame gives
// one_thread_s / serial_s. 0 for a non-positive time or thread count.
double amdahl_bound(double one_thread_s, double serial_s, int threads);

// The same bound on this machine: the split part runs `ceiling` times as fast as
// on one thread instead of `threads` times, where `ceiling` is the machine's own
// speed-up for independent work on `threads` threads measured just before the
// row (parallel_ceiling: a cache-resident loop per thread), taken in [1, threads]:
// one_thread_s / (serial_s + (one_thread_s - serial_s) / ceiling). A frame that
// reaches it loses nothing beyond its serial part and what the machine itself
// loses when its cores run at once (docs/performance.md 33). 0 as amdahl_bound
// for nonsense, and for a ceiling that is not a positive number.
double machine_bound(double one_thread_s, double serial_s, int threads, double ceiling);

// A threaded frame taken apart (docs/performance.md 38): `frame_s`, `serial_s`
// and `wait_s` are the frame on several threads, its serial part and the time
// its calling thread waited in the pool's runs for the other threads' last
// tasks; `on_caller_s` and `on_caller_serial_s` the same frame with every split
// task on the calling thread (Context::set_split_on_caller) and its serial part.
// The split work is what the tasks cost on one core, on_caller_s -
// on_caller_serial_s (>= 0); the frame spent split_time_s = frame_s - serial_s -
// wait_s on it with every thread working, so it ran at speed = split_work_s /
// split_time_s, against the thread count and the machine's ceiling. serial_s +
// split_time_s + wait_s == frame_s. All 0 for nonsense (a time that is not a
// positive number or a negative part) or no time left for the split work.
struct ThreadedFrameParts {
  double split_work_s = 0, split_time_s = 0, speed = 0;
};
ThreadedFrameParts threaded_frame_parts(double frame_s, double serial_s, double wait_s, double on_caller_s,
                                        double on_caller_serial_s);

// This machine's CPUs one at a time: for each CPU the process may run on (its
// affinity mask, at most 64 CPUs), the seconds a thread pinned there takes for
// the parallel ceiling's loop (a 256 KB buffer, no shared data), best of
// `repeats`; in CPU order. The CPUs of a virtual machine need not run at one
// speed: one vCPU's host core may be shared with a neighbour, and which CPU a
// one-thread frame runs on then sets its time (docs/performance.md 34.2).
// Empty where the affinity mask cannot be read or set (not Linux).
struct CpuSpeed {
  int cpu = 0;
  double seconds = 0;
};
std::vector<CpuSpeed> cpu_speeds(int repeats);
// One line for the table: "cpu0 12.34 ms, cpu1 8.01 ms (slowest 0.65 of the
// fastest)", or "one CPU: cpu0 8.01 ms", or "not measured".
std::string describe_cpu_speeds(const std::vector<CpuSpeed>& speeds);

}  // namespace ffsim::bench
