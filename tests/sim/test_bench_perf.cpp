// `ffsim bench --perf` (sim/bench/perf.cpp) on a tiny configuration: it runs every
// stage set-up of traces/perf/, counts the fragments each pass produces and writes
// its CSV. The fragment counts are derived by hand: a full-window quad or CopyPixels
// of a 32 x 32 window makes 32 * 32 = 1024 fragments, the upload 32 * 32 texels.
// Timings are never checked (benchmarks, not timed tests).
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <unistd.h>
#ifdef __linux__
#include <sched.h>
#endif

#include "cli_test_util.h"
#include "sim/bench/perf.h"
#include "sim/cli/cli.h"

using namespace ffsim;
namespace fs = std::filesystem;

namespace {
using test::Run;
using test::run;
// The line of `text` that starts at the first `start` ("" when there is none);
// a `start` beginning with a newline matches at a line's start only.
std::string line_with(const std::string& text, const std::string& start) {
  auto at = text.find(start);
  if (at == std::string::npos) return {};
  if (!start.empty() && start.front() == '\n') ++at;
  return text.substr(at, text.find('\n', at) - at);
}
// The number printed right after `key` in `line` (the key must be there).
double number_after(const std::string& line, const std::string& key) {
  const std::size_t at = line.find(key);
  REQUIRE(at != std::string::npos);
  return std::stod(line.substr(at + key.size()));
}
std::vector<std::vector<std::string>> read_csv(const fs::path& p) {
  std::vector<std::vector<std::string>> rows;
  std::ifstream f(p);
  std::string line;
  while (std::getline(f, line)) {
    std::vector<std::string> cells;
    std::string cell;
    bool quoted = false;
    for (char c : line) {
      if (c == '"') quoted = !quoted;
      else if (c == ',' && !quoted) {
        cells.push_back(cell);
        cell.clear();
      } else cell += c;
    }
    cells.push_back(cell);
    rows.push_back(cells);
  }
  return rows;
}
}  // namespace

TEST_CASE("bench --perf: every stage runs and counts its fragments") {
  const fs::path dir = fs::temp_directory_path() / ("ffsim-perf-" + std::to_string(::getpid()));
  fs::remove_all(dir);
  const Run r = run({"bench", "--perf", "--only", "stages", "--size", "32", "--repeat", "1", "--traces",
                     FFSIM_SOURCE_DIR "/traces", "--out", dir.string()});
  INFO(r.err);
  REQUIRE(r.code == 0);
  CHECK(r.out.find("Per-stage throughput, one core, 32x32 window") != std::string::npos);
  const auto rows = read_csv(dir / "perf_stages.csv");
  REQUIRE(rows.size() == 11);  // header + 10 stages
  CHECK(rows[0][0] == "stage");
  CHECK(rows[0][2] == "fragments_per_pass");
  for (std::size_t i = 1; i < rows.size(); ++i) {
    INFO(rows[i][0]);
    REQUIRE(rows[i].size() == rows[0].size());
    CHECK(rows[i][1] == "32");
    CHECK(std::stod(rows[i][2]) == 1024);  // every fragment of the window, exactly once
    CHECK(std::stod(rows[i][6]) > 0);      // Mfragments/s is a positive number
  }
  CHECK(fs::exists(dir / "perf.md"));
  fs::remove_all(dir);
}

TEST_CASE("bench --perf: bad arguments are one-line usage errors") {
  for (const auto& args : std::vector<std::vector<std::string>>{{"bench", "--perf", "--repeat", "0"},
                                                                {"bench", "--perf", "--only", "everything"},
                                                                {"bench", "--perf", "--threads", "1,x"},
                                                                {"bench", "--perf", "--size"},
                                                                {"bench", "--perf", "--frob"}}) {
    const Run r = run(args);
    CHECK(r.code == 2);
    CHECK(r.err.rfind("ffsim bench --perf: ", 0) == 0);
    CHECK(r.err.find('\n') == r.err.size() - 1);
  }
  const Run missing = run({"bench", "--perf", "--only", "stages", "--size", "16", "--repeat", "1", "--traces", "/nonexistent",
                           "--out", (fs::temp_directory_path() / "ffsim-perf-missing").string()});
  CHECK(missing.code == 1);
  CHECK(missing.err.find("/nonexistent/perf/quad-replace.trace") != std::string::npos);
  // --trace with a trace error: one line naming file:line:column once, then the message.
  const fs::path bad = fs::temp_directory_path() / "ffsim-perf-bad.trace";
  {
    std::ofstream f(bad);
    f << "ffsim-trace 1\nparam w 4 \"w\"\nparam w 5 \"again\"\n";
  }
  const Run dup = run({"bench", "--perf", "--trace", bad.string(), "--repeat", "1"});
  CHECK(dup.code == 1);
  const std::string where = bad.string() + ":3:7: ";
  CHECK(dup.err.rfind("ffsim bench --perf: " + where + "parameter `w` is already declared at " + bad.string() + ":2:7", 0) == 0);
  CHECK(dup.err.find(where, dup.err.find(where) + 1) == std::string::npos);
  std::error_code ec;
  fs::remove(bad, ec);
  fs::remove_all(fs::temp_directory_path() / "ffsim-perf-missing", ec);
}

TEST_CASE("bench --perf --trace: one thread prints the frame, two also the serial part and the machine's ceiling") {
  // The polygon scene at its small defaults (64x64, 64^2 maps, 16 rays).
  const std::vector<std::string> base{"bench", "--perf", "--trace", FFSIM_SOURCE_DIR "/traces/kautz-geforce-aa.trace",
                                      "--set", "rays=16", "--repeat", "1"};
  const Run one = run(base);
  REQUIRE(one.code == 0);
  CHECK(one.out.find(" frames/s, ") != std::string::npos);
  CHECK(one.out.find("serial part") == std::string::npos);
  CHECK(one.out.find("parallel ceiling") == std::string::npos);
  CHECK(one.out.find("each CPU alone after these frames (a cache-resident loop on one pinned thread): cpu") != std::string::npos);
  std::vector<std::string> args = base;
  args.insert(args.end(), {"--threads", "2"});
  const Run two = run(args);
  REQUIRE(two.code == 0);
  CHECK(two.out.find("serial part (this thread outside the pool's runs): median ") != std::string::npos);
  const std::size_t at = two.out.find("parallel ceiling of this machine just before these frames");
  REQUIRE(at != std::string::npos);
  // The bound's divisor is the ceiling taken in [1, 2].
  const std::size_t d = two.out.find("(T1 - serial) / ", at);
  REQUIRE(d != std::string::npos);
  const double c = std::stod(two.out.substr(d + 16));
  CHECK(c >= 1.0);
  CHECK(c <= 2.0);
}

TEST_CASE("bench --perf --trace --threads 1,2: each count's frames, its median and its speed-up against the first") {
  const Run r = run({"bench", "--perf", "--trace", FFSIM_SOURCE_DIR "/traces/kautz-geforce-aa.trace", "--set", "rays=16",
                     "--repeat", "3", "--threads", "1,2"});
  INFO(r.err);
  REQUIRE(r.code == 0);
  CHECK(r.out.find("; 3 frames per thread count, one count after the other\n") != std::string::npos);
  const std::size_t one = r.out.find("\n  1 thread:  median ");
  const std::size_t two = r.out.find("\n  2 threads: median ");
  REQUIRE(one != std::string::npos);
  REQUIRE(two != std::string::npos);
  CHECK(one < two);  // (in the order given)
  const std::string line = r.out.substr(two + 1, r.out.find('\n', two + 1) - two - 1);
  CHECK(line.find("; serial part ") != std::string::npos);
  // The speed-up is the one-thread median over the two-thread median, as printed (3 decimals).
  const std::string first = r.out.substr(one + 1, r.out.find('\n', one + 1) - one - 1);
  const double t1 = std::stod(first.substr(first.find("median ") + 7));
  const double t2 = std::stod(line.substr(line.find("median ") + 7));
  const std::string key = "speed-up against 1 (ratio of the medians) ";
  const std::size_t sp = line.find(key);
  REQUIRE(sp != std::string::npos);
  CHECK(std::stod(line.substr(sp + key.size())) == doctest::Approx(t1 / t2).epsilon(0.02));
  CHECK(line.find(", Amdahl bound ") != std::string::npos);
  CHECK(line.find(", machine bound ") != std::string::npos);
  // The one-thread line is the reference: neither a serial part nor a speed-up.
  CHECK(first.find("serial part") == std::string::npos);
  CHECK(first.find("speed-up") == std::string::npos);
  CHECK(r.out.find("each CPU alone after these frames") != std::string::npos);
  // The two-thread frame taken apart (performance.md 38): the frames with every
  // split task on this thread, their ratio to the one-thread frame as printed,
  // and the parts, which add up to the two-thread median.
  const std::string caller = line_with(r.out, "\n  2 threads, every split task on this thread (the workers idle): median ");
  REQUIRE_FALSE(caller.empty());
  const double tc = std::stod(caller.substr(caller.find("median ") + 7));
  const std::size_t x = caller.find(" ms, ");
  REQUIRE(x != std::string::npos);
  CHECK(std::stod(caller.substr(x + 5)) == doctest::Approx(tc / t1).epsilon(0.02));
  CHECK(caller.find("x the 1-thread frame; serial part ") != std::string::npos);
  const std::string apart = line_with(r.out, "\n  2 threads taken apart: serial part ");
  REQUIRE_FALSE(apart.empty());
  auto after = [&apart](const std::string& key) { return number_after(apart, key); };
  // serial + split time + waits is the two-thread median, and the split work over
  // the split time is the printed speed (each as printed, 3 decimals).
  const double serial = after("serial part "), work = after(" + split work "), speed = after(" ms on one core at ");
  const double split_time = after("x) = "), waits = after(" + the caller's waits for the other threads' last tasks ");
  CHECK(after(" (machine ceiling ") > 0);
  const std::size_t eq = apart.rfind(" = ");
  REQUIRE(eq != std::string::npos);
  const double total = std::stod(apart.substr(eq + 3));
  CHECK(total == doctest::Approx(t2).epsilon(0.001));
  CHECK(serial + split_time + waits == doctest::Approx(total).epsilon(0.01));
  CHECK(waits >= 0);
  CHECK(work / split_time == doctest::Approx(speed).epsilon(0.02));
  // The split work is the on-caller frame less its serial part.
  const double oc_serial = std::stod(caller.substr(caller.find("serial part ") + 12));
  CHECK(work == doctest::Approx(tc - oc_serial).epsilon(0.01));
  // The pool's runs (performance.md 40.2): as many in every frame, so the mean
  // wait a run times the runs is the frame's waits above (as printed: 3 decimals
  // of a ms, 2 of a us); the other thread's start is a positive time.
  const std::string runs_line = line_with(r.out, "\n  2 threads' pool runs: ");
  REQUIRE_FALSE(runs_line.empty());
  auto in_runs = [&runs_line](const std::string& key) { return number_after(runs_line, key); };
  const double runs = in_runs("pool runs: "), start_us = in_runs("took its first task "),
               wait_us = in_runs("the caller waited ");
  CHECK(runs >= 1);
  CHECK(runs == std::floor(runs));
  CHECK(start_us > 0);  // (a run takes a lock and reads the clock: never 0.00 us)
  // (each printed value within half its last digit: 0.0005 ms, and 0.005 us a run)
  CHECK(std::abs(wait_us * runs / 1e3 - waits) <= 0.0005 + runs * 0.005e-3 + 1e-9);
}

TEST_CASE("bench --perf --trace --threads 2,1: no first count of one, nothing taken apart") {
  const Run r = run({"bench", "--perf", "--trace", FFSIM_SOURCE_DIR "/traces/kautz-geforce-aa.trace", "--set", "rays=16",
                     "--repeat", "1", "--threads", "2,1"});
  INFO(r.err);
  REQUIRE(r.code == 0);
  CHECK(r.out.find("\n  2 threads: median ") != std::string::npos);
  CHECK(r.out.find("every split task on this thread") == std::string::npos);
  CHECK(r.out.find("taken apart") == std::string::npos);
}

// (One run, at --quick and --repeat 1: under the sanitizers it still takes a
// few minutes, the longest test of the ASan build.)
TEST_CASE("bench --perf: the threads table prints each speed-up and the machine's ceiling beside it") {
  const fs::path dir = fs::temp_directory_path() / ("ffsim-perf-threads-" + std::to_string(::getpid()));
  fs::remove_all(dir);
  const Run r = run({"bench", "--perf", "--only", "threads", "--quick", "--repeat", "1", "--threads", "1,2",
                     "--traces", FFSIM_SOURCE_DIR "/traces", "--out", dir.string()});
  INFO(r.err);
  REQUIRE(r.code == 0);
  auto count = [](const std::string& s, const std::string& what) {
    int n = 0;
    for (auto at = s.find(what); at != std::string::npos; at = s.find(what, at + 1)) ++n;
    return n;
  };
  // One speed-up per trace, scene and window at 2 threads (3 traces x the terrain
  // at two windows and the polygon), and the ceiling for 2 threads before and
  // after the table.
  const std::string speedups = line_with(r.out, "speed-up against one thread: ");
  CHECK(count(speedups, " 2 threads ") == 9);
  CHECK(count(speedups, "kautz-geforce-aa terrain 160x120 2 threads ") == 1);
  CHECK(count(speedups, "kautz-geforce-aa terrain 320x240 2 threads ") == 1);
  CHECK(count(speedups, "kautz-geforce-aa polygon 256x256 2 threads ") == 1);
  const std::string ceiling = line_with(r.out, "parallel ceiling of this machine");
  CHECK(count(ceiling, "2 threads ") == 2);
  std::ifstream md(dir / "perf.md");
  std::stringstream text;
  text << md.rdbuf();
  CHECK(text.str().find("Speed-up against one thread (medians): ") != std::string::npos);
  CHECK(text.str().find("Parallel ceiling of this machine, measured just before / after this table") != std::string::npos);
  // Each threaded row's serial part and Amdahl's bound: one line each, in the
  // text, perf.md's table and perf_threads_serial.csv (header and 9 rows).
  CHECK(count(r.out, " 2 threads: serial ") == 9);
  CHECK(count(r.out, ", Amdahl bound ") == 9);
  CHECK(count(r.out, "; machine ceiling ") == 9);
  CHECK(text.str().find("| trace | scene | window | threads | frame ms | serial ms | serial share | speed-up | Amdahl bound | "
                        "machine ceiling | machine bound |") != std::string::npos);
  const auto split_rows = read_csv(dir / "perf_threads_serial.csv");
  REQUIRE(split_rows.size() == 10);
  CHECK(split_rows[0] == std::vector<std::string>{"trace", "scene", "width", "height", "threads", "median_s", "serial_median_s",
                                                  "one_thread_median_s", "speedup", "amdahl_bound", "machine_ceiling",
                                                  "machine_bound"});
  for (std::size_t i = 1; i < split_rows.size(); ++i) {
    REQUIRE(split_rows[i].size() == 12);
    CHECK(split_rows[i][4] == "2");
    // The serial part is a part of the frame; the bound is above 0 and at most
    // the thread count.
    const double median = std::stod(split_rows[i][5]), serial = std::stod(split_rows[i][6]);
    const double bound = std::stod(split_rows[i][9]);
    CHECK(serial >= 0);
    CHECK(serial <= median);
    CHECK(bound > 0);
    CHECK(bound <= 2.0 + 1e-9);
    // The machine bound is Amdahl's with the split part at the row's ceiling
    // (clamped to [1, threads]): at most Amdahl's, and what machine_bound gives.
    const double ceiling = std::stod(split_rows[i][10]), mbound = std::stod(split_rows[i][11]);
    CHECK(ceiling > 0);
    CHECK(mbound > 0);
    CHECK(mbound <= bound + 1e-9);
    CHECK(mbound == doctest::Approx(ffsim::bench::machine_bound(std::stod(split_rows[i][7]), serial, 2, ceiling)));
  }
  fs::remove_all(dir);
}

TEST_CASE("bench --perf: the machine bound, hand-derived values") {
  using ffsim::bench::machine_bound;
  // 4 ms on one thread, 1 ms serial, 2 threads on a machine whose ceiling is
  // 1.5x: 4 / (1 + 3/1.5) = 4/3.
  CHECK(machine_bound(4e-3, 1e-3, 2, 1.5) == doctest::Approx(4.0 / 3.0));
  // A ceiling of the thread count: Amdahl's bound, 4 / (1 + 3/2) = 1.6; above
  // it (noise): clamped to the thread count; below 1 (a loaded machine): 1, so
  // the bound is 1 (no split part can run slower than on one thread here).
  CHECK(machine_bound(4e-3, 1e-3, 2, 2.0) == doctest::Approx(1.6));
  CHECK(machine_bound(4e-3, 1e-3, 2, 2.3) == doctest::Approx(1.6));
  CHECK(machine_bound(4e-3, 1e-3, 2, 0.8) == doctest::Approx(1.0));
  // No serial part: the ceiling itself.
  CHECK(machine_bound(4e-3, 0, 2, 1.7) == doctest::Approx(1.7));
  // Nonsense in, 0 out (never NaN or Inf): no ceiling measured, NaN, bad times.
  CHECK(machine_bound(4e-3, 1e-3, 2, 0) == 0);
  CHECK(machine_bound(4e-3, 1e-3, 2, std::nan("")) == 0);
  CHECK(machine_bound(0, 1e-3, 2, 1.5) == 0);
  CHECK(machine_bound(4e-3, 1e-3, 0, 1.5) == 0);
}

TEST_CASE("bench --perf: a threaded frame taken apart, hand-derived values") {
  using ffsim::bench::threaded_frame_parts;
  // 4 ms on 2 threads: 1 ms serial, 0.5 ms of waits, so 2.5 ms of split time;
  // with every task on the caller 5 ms, of which 1 ms serial: 4 ms of split
  // work, which ran at 4 / 2.5 = 1.6x.
  auto p = threaded_frame_parts(4e-3, 1e-3, 0.5e-3, 5e-3, 1e-3);
  CHECK(p.split_work_s == doctest::Approx(4e-3));
  CHECK(p.split_time_s == doctest::Approx(2.5e-3));
  CHECK(p.speed == doctest::Approx(1.6));
  // A serial part longer than the on-caller frame: no split work, not a negative one.
  p = threaded_frame_parts(4e-3, 1e-3, 0, 1e-3, 2e-3);
  CHECK(p.split_work_s == 0);
  CHECK(p.split_time_s == doctest::Approx(3e-3));
  CHECK(p.speed == 0);
  // Nonsense in, zeros out (never NaN or Inf): bad or missing times, negative
  // parts, no time left for the split work.
  for (const auto& q : {threaded_frame_parts(0, 1e-3, 0, 5e-3, 1e-3), threaded_frame_parts(4e-3, -1e-3, 0, 5e-3, 1e-3),
                        threaded_frame_parts(4e-3, 1e-3, -1e-3, 5e-3, 1e-3), threaded_frame_parts(4e-3, 1e-3, 0, 0, 1e-3),
                        threaded_frame_parts(4e-3, 1e-3, 0, std::nan(""), 1e-3),
                        threaded_frame_parts(std::numeric_limits<double>::infinity(), 1e-3, 0, 5e-3, 1e-3),
                        threaded_frame_parts(4e-3, 3e-3, 1e-3, 5e-3, 1e-3)}) {
    CHECK(q.split_work_s == 0);
    CHECK(q.split_time_s == 0);
    CHECK(q.speed == 0);
  }
}

TEST_CASE("bench --perf: Amdahl's bound, hand-derived values") {
  using ffsim::bench::amdahl_bound;
  // 4 ms on one thread, 1 ms serial, 2 threads: 4 / (1 + 3/2) = 1.6.
  CHECK(amdahl_bound(4e-3, 1e-3, 2) == doctest::Approx(1.6));
  // 3 threads: 4 / (1 + 1) = 2; no serial part: the thread count; all serial: 1.
  CHECK(amdahl_bound(4e-3, 1e-3, 3) == doctest::Approx(2.0));
  CHECK(amdahl_bound(4e-3, 0, 2) == doctest::Approx(2.0));
  CHECK(amdahl_bound(4e-3, 4e-3, 2) == doctest::Approx(1.0));
  // A serial part longer than the one-thread frame (the split's own set-up): T1 / S.
  CHECK(amdahl_bound(2e-3, 4e-3, 2) == doctest::Approx(0.5));
  // One thread: 1 whatever the serial part.
  CHECK(amdahl_bound(4e-3, 1e-3, 1) == doctest::Approx(1.0));
  // Nonsense in, 0 out (never NaN or Inf).
  CHECK(amdahl_bound(0, 1e-3, 2) == 0);
  CHECK(amdahl_bound(4e-3, -1, 2) == 0);
  CHECK(amdahl_bound(4e-3, 1e-3, 0) == 0);
  CHECK(amdahl_bound(std::nan(""), 1e-3, 2) == 0);
}

TEST_CASE("bench --perf: each CPU's speed alone, one entry per CPU of the affinity mask, and its line") {
  const std::vector<bench::CpuSpeed> speeds = bench::cpu_speeds(1);
#ifdef __linux__
  cpu_set_t allowed;
  CPU_ZERO(&allowed);
  REQUIRE(sched_getaffinity(0, sizeof allowed, &allowed) == 0);
  REQUIRE(static_cast<int>(speeds.size()) == std::min(CPU_COUNT(&allowed), 64));
  for (std::size_t i = 0; i < speeds.size(); ++i) {
    CHECK(CPU_ISSET(speeds[i].cpu, &allowed));
    if (i) CHECK(speeds[i].cpu > speeds[i - 1].cpu);
    CHECK(speeds[i].seconds > 0);
    CHECK(speeds[i].seconds < 10);
  }
  // The caller's own mask is left as it was.
  cpu_set_t after;
  CPU_ZERO(&after);
  REQUIRE(sched_getaffinity(0, sizeof after, &after) == 0);
  CHECK(CPU_EQUAL(&allowed, &after));
#endif
  // The line, on hand-made numbers.
  CHECK(bench::describe_cpu_speeds({}) == "not measured");
  CHECK(bench::describe_cpu_speeds({{3, 0.008}}) == "one CPU: cpu3 8.00 ms");
  CHECK(bench::describe_cpu_speeds({{0, 0.012}, {1, 0.006}}) == "cpu0 12.00 ms, cpu1 6.00 ms (slowest 0.50 of the fastest)");
}
