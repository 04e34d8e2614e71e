// `ffsim bench --perf` (issue 10). Four tables, each also written as CSV:
//
//  1. stages   per-stage throughput on one core: a set-up trace under traces/perf/
//              is replayed once, then its timed pass (a full-window quad, a
//              CopyPixels, or a texture upload) repeatedly on the same Context;
//              Mfragments/s = fragments entering the per-fragment operations (or
//              texels uploaded) / time, median of the repeats.
//  2. traces   whole paper traces (load excluded; outputs skipped): frames/s.
//  3. scaling  frames/s over window sizes 256^2 .. 2048^2.
//  4. threads  frames/s over worker thread counts.
//
// Beside each time: the memory-bandwidth floor, the bytes the pass must read and
// write in ffsim's own storage (16-bit colour codes, 8-bit stencil, 32-bit depth)
// divided by this machine's measured copy bandwidth. Nothing here fails on a
// number; the numbers go to the table, docs/results/perf_*.csv and perf.md.
#include "sim/bench/perf.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <memory>
#include <ostream>
#include <sstream>
#include <thread>
#include <vector>

#ifdef __linux__
#include <pthread.h>
#include <sched.h>
#endif

#include "pipeline/gl/enums.h"
#include "sim/bench/accuracy_metrics.h"
#include "sim/bench/svg_plot.h"
#include "sim/cli/cli.h"
#include "sim/context.h"
#include "sim/trace/executor.h"
#include "sim/trace/trace.h"

namespace ffsim::bench {

namespace fs = std::filesystem;

namespace {

using Clock = std::chrono::steady_clock;
using Sets = std::vector<std::pair<std::string, std::string>>;

struct Options {
  bool quick = false;
  std::string traces_dir = "traces";
  std::string out_dir = "docs/results";
  int repeat = 7;
  int stage_size = 0;  // 0: 1024 (256 with --quick)
  bool stages = true, traces = true, scaling = true, threads = true;
  std::vector<int> thread_counts;  // empty: 1 .. hardware threads
  std::string trace_file;          // --trace FILE: time this trace alone
  Sets sets;                       // --set NAME=EXPR for --trace
};

// Repeated timings (seconds): median, minimum and maximum (sim/bench/accuracy_metrics.h).
using Timing = Spread;

double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

std::string fixed(double v, int digits) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", digits, v);
  return buf;
}

// Copy bandwidth of this machine in bytes per second, counting the bytes read plus
// the bytes written (2 x the buffer per memcpy): best of the repeats, buffers much
// larger than the caches.
double copy_bandwidth(std::size_t bytes, int repeats) {
  std::vector<unsigned char> a(bytes, 1), b(bytes, 2);
  double best = 0;
  for (int r = 0; r < repeats; ++r) {
    const auto t0 = Clock::now();
    std::memcpy(r % 2 ? a.data() : b.data(), r % 2 ? b.data() : a.data(), bytes);
    const double t = seconds_since(t0);
    if (t > 0) best = std::max(best, 2.0 * static_cast<double>(bytes) / t);
  }
  return best;
}

// This machine's own ceiling for `n` threads: a loop over a 256 KB buffer per
// thread (multiply-xorshift of 32-bit words: the caches and the ALUs, no shared
// data) timed on one thread, then on n threads at once; returns n x the one
// thread's time / the n threads' time, best of the repeats of each. About n when
// n cores are free and run at one speed; less when the cores are shared (a
// virtual machine's neighbours) or slow down together. The speed-up of a trace
// at n threads is read against it (docs/performance.md 24.3).
volatile std::uint32_t ceiling_sink = 0;
// The loop itself (also cpu_speeds'): multiply-xorshift over the buffer, 2048 times.
void ceiling_work(std::vector<std::uint32_t>& buf) {
  for (std::uint32_t r = 0; r < 2048; ++r)
    for (std::uint32_t& x : buf) {
      x = (x ^ r) * 0x85EBCA6Bu;
      x ^= x >> 13;
    }
}
double parallel_ceiling(int n, int repeats) {
  std::vector<std::vector<std::uint32_t>> bufs(static_cast<std::size_t>(n), std::vector<std::uint32_t>(65536, 1));
  auto timed = [&](int threads) {
    double best = 1e300;
    for (int r = 0; r < repeats; ++r) {
      const auto t0 = Clock::now();
      std::vector<std::thread> others;
      for (int k = 1; k < threads; ++k) others.emplace_back(ceiling_work, std::ref(bufs[static_cast<std::size_t>(k)]));
      ceiling_work(bufs[0]);
      for (std::thread& t : others) t.join();
      best = std::min(best, seconds_since(t0));
    }
    return best;
  };
  const double one = timed(1), all = timed(n);
  for (const auto& b : bufs) ceiling_sink = ceiling_sink ^ b[12345];  // the buffers are read: the loops must run
  return all > 0 ? n * one / all : 0;
}

}  // namespace

std::vector<CpuSpeed> cpu_speeds(int repeats) {
  std::vector<CpuSpeed> speeds;
#ifdef __linux__
  cpu_set_t allowed;
  CPU_ZERO(&allowed);
  if (sched_getaffinity(0, sizeof allowed, &allowed) != 0) return speeds;
  for (int cpu = 0; cpu < 64 && cpu < CPU_SETSIZE; ++cpu) {
    if (!CPU_ISSET(cpu, &allowed)) continue;
    double best = 0;
    bool pinned = false;
    std::thread t([&] {  // (a thread of its own: the caller's affinity stays as it was)
      cpu_set_t one;
      CPU_ZERO(&one);
      CPU_SET(cpu, &one);
      if (pthread_setaffinity_np(pthread_self(), sizeof one, &one) != 0) return;
      pinned = true;
      std::vector<std::uint32_t> buf(65536, 1);
      best = 1e300;
      for (int r = 0; r < repeats; ++r) {
        const auto t0 = Clock::now();
        ceiling_work(buf);
        best = std::min(best, seconds_since(t0));
      }
      ceiling_sink = ceiling_sink ^ buf[12345];
    });
    t.join();
    if (!pinned) return {};
    speeds.push_back({cpu, best});
  }
#else
  (void)repeats;
#endif
  return speeds;
}

std::string describe_cpu_speeds(const std::vector<CpuSpeed>& speeds) {
  if (speeds.empty()) return "not measured";
  std::string s = speeds.size() == 1 ? "one CPU: " : "";
  double lo = speeds.front().seconds, hi = lo;
  for (std::size_t i = 0; i < speeds.size(); ++i) {
    s += (i ? ", cpu" : "cpu") + std::to_string(speeds[i].cpu) + " " + fixed(speeds[i].seconds * 1e3, 2) + " ms";
    lo = std::min(lo, speeds[i].seconds);
    hi = std::max(hi, speeds[i].seconds);
  }
  if (speeds.size() > 1 && hi > 0) s += " (slowest " + fixed(lo / hi, 2) + " of the fastest)";
  return s;
}

namespace {

// The speed-up the split part of a frame can have on this machine: its ceiling
// for `threads` threads, taken in [1, threads] (machine_bound).
double machine_speed(int threads, double ceiling) { return std::clamp(ceiling, 1.0, static_cast<double>(threads)); }

trace::Program load(const std::string& path, const Sets& sets) {
  trace::LoadOptions lo;
  lo.sets = sets;
  return trace::load_trace_file(path, lo);
}

trace::RunOptions quiet_run(int threads) {
  trace::RunOptions ro;
  ro.outputs = false;  // no dumps, hashes or expects: the GL work alone
  ro.threads = threads;
  return ro;
}

void check(const trace::RunResult& r, const std::string& what) {
  if (!r.ok) throw std::runtime_error(what + ": " + r.fatal);
  if (!r.gl_errors.empty()) throw std::runtime_error(what + ": " + r.gl_errors.front());
}

// ---- 1. stages ---------------------------------------------------------------

struct Stage {
  std::string name;
  std::string setup;      // traces/perf/<setup>.trace
  std::string pass;       // traces/perf/<pass>.trace; empty: the texture upload
  int mag = 1;            // pixels per texel
  double bytes = 0;       // bytes per fragment the pass must read + write
  std::string bytes_note;
  bool same_image = false;  // the upload: the same image every time (the upload cache's hit), else a new one
};

std::vector<Stage> stages() {
  // Colour is stored as 16-bit codes (4 channels: 8 B), stencil 1 B, depth 4 B.
  // The 64^2 textures stay in the caches and are not counted.
  return {
      {"quad REPLACE (texel-aligned)", "quad-replace", "pass-quad", 1, 8, "colour write 8 B"},
      {"quad REPLACE (2x magnified)", "quad-replace", "pass-quad", 2, 8, "colour write 8 B"},
      {"quad ADD blend", "quad-add", "pass-quad", 1, 16, "colour read + write 16 B"},
      {"quad ADD blend (2x magnified)", "quad-add", "pass-quad", 2, 16, "colour read + write 16 B"},
      {"quad SUBTRACT blend", "quad-subtract", "pass-quad", 1, 16, "colour read + write 16 B"},
      {"combiners: shadow test, 2 bilinear units", "combiner-shadow", "pass-quad", 1, 2, "alpha write 2 B"},
      {"combiners: shadow test (2x magnified)", "combiner-shadow", "pass-quad", 2, 2, "alpha write 2 B"},
      {"CopyPixels + alpha test + stencil INCR", "copypixels-stencil", "pass-copypixels", 1, 10,
       "colour read 8 B + stencil read + write 2 B"},
      {"texture upload: colour matrix + post-CM table", "upload-transfer", "", 1, 6,
       "client RGBA8 read 4 B + texel write 2 B"},
      {"texture upload, same image (cache hit)", "upload-transfer", "", 1, 6,
       "client RGBA8 read 4 B + texel write 2 B", true},
  };
}

struct StageRow {
  Stage stage;
  int w = 0;
  double fragments = 0;  // per pass
  Timing t;
};

StageRow run_stage(const Options& o, const Stage& st, int w, int repeat) {
  const fs::path dir = fs::path(o.traces_dir) / "perf";
  const Sets sets = {{"w", std::to_string(w)}, {"mag", std::to_string(st.mag)}};
  const trace::Program setup = load((dir / (st.setup + ".trace")).string(), sets);
  Context ctx(setup.profile, setup.width, setup.height);
  std::ostringstream sink;
  check(trace::run_program_on(ctx, setup, quiet_run(1), sink), st.setup);

  std::function<void()> pass;
  std::function<double()> count;
  std::unique_ptr<trace::Program> pass_prog;
  std::vector<std::uint8_t> client;
  if (!st.pass.empty()) {
    const Sets pass_sets = st.pass == "pass-quad" ? sets : Sets{sets.front()};  // only pass-quad takes mag
    pass_prog = std::make_unique<trace::Program>(load((dir / (st.pass + ".trace")).string(), pass_sets));
    pass = [&] { check(trace::run_program_on(ctx, *pass_prog, quiet_run(1), sink), st.pass); };
  } else {
    // Biased normals (c + 1)/2 of a fixed pseudo-random pattern (xorshift32).
    client.resize(4 * static_cast<std::size_t>(w) * static_cast<std::size_t>(w));
    std::uint32_t x = 2463534242u;
    for (std::size_t i = 0; i < client.size(); ++i) {
      x ^= x << 13;
      x ^= x >> 17;
      x ^= x << 5;
      client[i] = (i % 4 == 3) ? 255 : static_cast<std::uint8_t>(x >> 24);
    }
    // A new image every time (one byte changed: the upload cache misses and the
    // upload is computed), or the same image again (the cache's hit).
    const bool same = st.same_image;
    pass = [&, same] {
      if (!same) ++client[0];
      ctx.texImage2D(gl::TEXTURE_2D, 0, gl::ALPHA8, w, w, 0, gl::RGBA, gl::UNSIGNED_BYTE, client.data());
      if (ctx.getError() != gl::NO_ERROR) throw std::runtime_error("texture upload: GL error");
    };
  }
  StageRow row;
  row.stage = st;
  row.w = w;
  const std::uint64_t f0 = ctx.fragments_written();
  pass();  // warm-up
  const std::uint64_t f1 = ctx.fragments_written();
  row.fragments = st.pass.empty() ? static_cast<double>(w) * w : static_cast<double>(f1 - f0);
  std::vector<double> times;
  for (int r = 0; r < repeat; ++r) {
    const auto t0 = Clock::now();
    pass();
    times.push_back(seconds_since(t0));
  }
  row.t = spread(times);
  return row;
}

// ---- 2-4. whole traces ---------------------------------------------------------

struct TraceCase {
  std::string trace;  // stem under traces/
  std::string scene;  // "polygon" or "terrain"
  int width = 0, height = 0;
  int threads = 1;
};

std::string window_name(const TraceCase& c) { return std::to_string(c.width) + "x" + std::to_string(c.height); }

struct TraceRow {
  TraceCase c;
  int passes = 0;
  double fragments = 0;  // per frame
  Timing t;              // seconds per frame
  Timing serial;         // of each frame, seconds the calling thread spent outside the pool's runs
  Timing wait;           // of each frame, seconds the calling thread waited in the pool's runs for other threads
  // Threads: the pool's runs a frame (the same in every frame: they follow the
  // trace, not the clock), and per run, the mean of how long after it began
  // another thread took its first task, and of the caller's wait (medians over
  // the frames; Context::pool_runs, pool_start_seconds, pool_wait_seconds).
  std::uint64_t pool_runs = 0;
  Timing start_per_run, wait_per_run;
  double ceiling = 0;    // threads > 1 in the threads table: parallel_ceiling just before the row
};

Sets scene_sets(const TraceCase& c) {
  if (c.scene == "polygon")  // the 64^2 maps, magnified to the window (bilinear)
    return {{"scene", "0"}, {"res", "64"}, {"zoom", fixed(c.width / 64.0, 6)}};
  return {{"scene", "1"}, {"res", "128"}, {"tw", std::to_string(c.width)}, {"th", std::to_string(c.height)}};
}

// `repeat` frames of `prog` on c.threads threads, each on a fresh Context, after
// one warm-up frame (which gives the fragment count), back to back. on_caller:
// every split task on the calling thread (Context::set_split_on_caller).
TraceRow run_frames(const trace::Program& prog, const std::string& label, const TraceCase& c, int repeat,
                    bool on_caller = false) {
  TraceRow row;
  row.c = c;
  row.passes = prog.pass_count();
  std::ostringstream sink;
  std::vector<double> times, serial, wait, start_per_run, wait_per_run;
  for (int r = 0; r <= repeat; ++r) {  // r = 0: warm-up
    Context ctx(prog.profile, prog.width, prog.height);
    ctx.set_split_on_caller(on_caller);
    const auto t0 = Clock::now();
    check(trace::run_program_on(ctx, prog, quiet_run(c.threads), sink), label);
    const double t = seconds_since(t0);
    if (r == 0) {
      row.fragments = static_cast<double>(ctx.fragments_written());
    } else {
      times.push_back(t);
      serial.push_back(std::max(0.0, t - ctx.pool_seconds()));
      wait.push_back(ctx.pool_wait_seconds());
      if ((row.pool_runs = ctx.pool_runs()) > 0) {
        const auto runs = static_cast<double>(row.pool_runs);
        start_per_run.push_back(ctx.pool_start_seconds() / runs);
        wait_per_run.push_back(ctx.pool_wait_seconds() / runs);
      }
    }
  }
  row.t = spread(times);
  row.serial = spread(serial);
  row.wait = spread(wait);
  row.start_per_run = spread(start_per_run);  // (NaN without pool runs: not printed)
  row.wait_per_run = spread(wait_per_run);
  return row;
}

TraceRow run_trace_case(const Options& o, const TraceCase& c, int repeat) {
  return run_frames(load((fs::path(o.traces_dir) / (c.trace + ".trace")).string(), scene_sets(c)), c.trace, c, repeat);
}

// Lower bound per fragment of a paper pass: every pass depth-tests (reads 4 B of
// depth) and writes at least the 1-byte stencil or one 2-byte colour channel.
constexpr double kTraceBytesPerFragment = 5;

// ---- output --------------------------------------------------------------------

// Frames/s against pixels (or threads), log-log, one series per (trace, scene), and
// beside each series the ideal: linear in pixels (fps x pixels constant) or in
// threads, from its first point.
Plot scaling_plot(const std::vector<TraceRow>& rows, bool threads) {
  Plot p;
  p.title = threads ? "ffsim bench --perf: frames/s against worker threads"
                    : "ffsim bench --perf: frames/s against pixels per frame, one thread";
  p.x_label = threads ? "worker threads" : "pixels per frame";
  p.y_label = "frames per second";
  p.x_log = p.y_log = true;
  p.label_points = false;
  for (const TraceRow& r : rows) {
    const std::string name = r.c.trace + " " + r.c.scene + (threads ? " " + window_name(r.c) : "");
    const double x = threads ? r.c.threads : static_cast<double>(r.c.width) * r.c.height;
    if (p.series.empty() || p.series.back().name != name) p.series.push_back({name, {}, ""});
    p.series.back().points.push_back({x, 1.0 / r.t.median, name + ": " + fixed(1.0 / r.t.median, 1) + " fps", false});
  }
  for (const PlotSeries& s : p.series) {
    if (s.points.size() < 2) continue;
    const PlotPoint& a = s.points.front();
    PlotLine l{"linear scaling from " + s.name, {}, "#bbbbbb"};
    for (const PlotPoint& q : s.points) l.points.emplace_back(q.x, threads ? a.y * q.x / a.x : a.y * a.x / q.x);
    p.lines.push_back(l);
  }
  return p;
}

struct Csv {
  std::ofstream f;
  Csv(const fs::path& p, const std::string& header) : f(p) { f << header << "\n"; }
};

std::string cell(std::string s, std::size_t w) {
  if (s.size() < w) s.append(w - s.size(), ' ');
  return s;
}

int parse_args(const std::vector<std::string>& args, Options& o, std::ostream& err) {
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    auto value = [&]() -> const std::string* { return i + 1 < args.size() ? &args[++i] : nullptr; };
    if (a == "--quick") o.quick = true;
    else if (a == "--traces") {
      const std::string* v = value();
      if (!v) return cli::usage_error(err, "bench --perf", "--traces expects a directory");
      o.traces_dir = *v;
    } else if (a == "--out") {
      const std::string* v = value();
      if (!v) return cli::usage_error(err, "bench --perf", "--out expects a directory");
      o.out_dir = *v;
    } else if (a == "--repeat") {
      const std::string* v = value();
      int n = 0;
      if (!v || std::sscanf(v->c_str(), "%d", &n) != 1 || n < 1 || n > 1000)
        return cli::usage_error(err, "bench --perf", "--repeat expects 1..1000");
      o.repeat = n;
    } else if (a == "--trace") {
      const std::string* v = value();
      if (!v) return cli::usage_error(err, "bench --perf", "--trace expects a trace file");
      o.trace_file = *v;
    } else if (a == "--set") {
      const std::string* v = value();
      if (!v) return cli::usage_error(err, "bench --perf", "--set expects NAME=EXPR");
      try {
        o.sets.push_back(trace::parse_set_argument(*v));
      } catch (const std::exception& e) {
        return cli::usage_error(err, "bench --perf", e.what());
      }
    } else if (a == "--size") {
      const std::string* v = value();
      int n = 0;
      if (!v || std::sscanf(v->c_str(), "%d", &n) != 1 || n < 16 || n > 4096)
        return cli::usage_error(err, "bench --perf", "--size expects 16..4096");
      o.stage_size = n;
    } else if (a == "--only") {
      const std::string* v = value();
      if (!v || (*v != "stages" && *v != "traces" && *v != "scaling" && *v != "threads"))
        return cli::usage_error(err, "bench --perf", "--only expects stages, traces, scaling or threads");
      o.stages = *v == "stages";
      o.traces = *v == "traces";
      o.scaling = *v == "scaling";
      o.threads = *v == "threads";
    } else if (a == "--threads") {
      const std::string* v = value();
      if (!v) return cli::usage_error(err, "bench --perf", "--threads expects a list like 1,2,4");
      std::stringstream ss(*v);
      std::string item;
      while (std::getline(ss, item, ',')) {
        int n = 0;
        if (std::sscanf(item.c_str(), "%d", &n) != 1 || n < 1 || n > 256)
          return cli::usage_error(err, "bench --perf", "--threads expects a list of 1..256 like 1,2,4");
        o.thread_counts.push_back(n);
      }
    } else return cli::usage_error(err, "bench --perf", "unknown argument `" + a + "`");
  }
  return 0;
}

// --trace FILE --threads A,B,...: the frames of each count back to back, as the
// threads table times its rows (a count's frames one after another: frame by
// frame alternation was measured to penalise the threaded frames, 28.5), the
// machine's ceiling just before each count's frames; each count's median and
// its speed-up against the first count (the ratio of the medians).
void time_counts(const Options& o, const trace::Program& prog, std::ostream& out) {
  std::vector<TraceRow> rows, on_caller;
  std::vector<double> ceiling;
  // After one thread, each count's frames are followed by the same frames with
  // every split task on this thread, which take its frame apart (performance.md 38).
  const bool apart = o.thread_counts.front() == 1;
  for (int n : o.thread_counts) {
    const TraceCase c{"", "", prog.width, prog.height, n};
    ceiling.push_back(n > 1 ? parallel_ceiling(n, 3) : 0);
    rows.push_back(run_frames(prog, o.trace_file, c, o.repeat));
    on_caller.push_back(apart && n > 1 ? run_frames(prog, o.trace_file, c, o.repeat, true) : TraceRow{});
  }
  out << o.trace_file << ": " << prog.width << "x" << prog.height << ", " << prog.pass_count() << " passes, "
      << static_cast<std::uint64_t>(rows[0].fragments) << " fragments; " << o.repeat
      << " frames per thread count, one count after the other\n";
  const double first = rows[0].t.median;
  for (std::size_t k = 0; k < rows.size(); ++k) {
    const int n = rows[k].c.threads;
    const Timing& t = rows[k].t;
    const double s = rows[k].serial.median;
    out << "  " << n << (n == 1 ? " thread:  " : " threads: ") << "median " << fixed(t.median * 1e3, 3) << " ms ("
        << fixed(t.min * 1e3, 3) << " .. " << fixed(t.max * 1e3, 3) << "), " << fixed(1 / t.median, 1) << " frames/s";
    if (n > 1) out << "; serial part " << fixed(s * 1e3, 3) << " ms";
    if (k > 0)
      out << "; speed-up against " << rows[0].c.threads << " (ratio of the medians) " << fixed(first / t.median, 2) << "x";
    if (k > 0 && rows[0].c.threads == 1 && n > 1)
      out << ", Amdahl bound " << fixed(amdahl_bound(first, s, n), 2) << "x, machine ceiling " << fixed(ceiling[k], 2)
          << "x, machine bound " << fixed(machine_bound(first, s, n, ceiling[k]), 2) << "x";
    out << "\n";
    if (!apart || n == 1) continue;
    const TraceRow& one = on_caller[k];
    const double wait = rows[k].wait.median;
    const ThreadedFrameParts p = threaded_frame_parts(t.median, s, wait, one.t.median, one.serial.median);
    out << "  " << n << " threads, every split task on this thread (the workers idle): median " << fixed(one.t.median * 1e3, 3)
        << " ms, " << fixed(one.t.median / first, 2) << "x the 1-thread frame; serial part " << fixed(one.serial.median * 1e3, 3)
        << " ms\n"
        << "  " << n << " threads taken apart: serial part " << fixed(s * 1e3, 3) << " + split work "
        << fixed(p.split_work_s * 1e3, 3) << " ms on one core at " << fixed(p.speed, 2) << "x (machine ceiling "
        << fixed(ceiling[k], 2) << "x) = " << fixed(p.split_time_s * 1e3, 3)
        << " + the caller's waits for the other threads' last tasks " << fixed(wait * 1e3, 3) << " = "
        << fixed(t.median * 1e3, 3) << " ms\n";
    if (rows[k].pool_runs > 0)  // (late starts against the last tasks' tails: performance.md 40.2)
      out << "  " << n << " threads' pool runs: " << rows[k].pool_runs << " a frame; in each, another thread took its first task "
          << fixed(rows[k].start_per_run.median * 1e6, 2) << " us after the run began, and the caller waited "
          << fixed(rows[k].wait_per_run.median * 1e6, 2) << " us for the last (means over a frame's runs, median frame)\n";
  }
  out << "each CPU alone after these frames (a cache-resident loop on one pinned thread): " << describe_cpu_speeds(cpu_speeds(3))
      << "\n";
}

// --trace FILE: load once, replay --repeat times on fresh Contexts (outputs off).
int time_one_trace(const Options& o, std::ostream& out, std::ostream& err) {
  try {
    const trace::Program prog = load(o.trace_file, o.sets);
    if (o.thread_counts.size() > 1) {
      time_counts(o, prog, out);
      return 0;
    }
    const int threads = o.thread_counts.empty() ? 1 : o.thread_counts.front();
    // The machine's ceiling for that many threads just before the frames, as the
    // threads table measures it before each row (docs/performance.md 33.3).
    const double ceiling = threads > 1 ? parallel_ceiling(threads, 3) : 0;
    const TraceRow row = run_frames(prog, o.trace_file, TraceCase{"", "", prog.width, prog.height, threads}, o.repeat);
    const auto fragments = static_cast<std::uint64_t>(row.fragments);
    const Timing& t = row.t;
    out << o.trace_file << ": " << prog.width << "x" << prog.height << ", " << prog.pass_count() << " passes, "
        << fragments << " fragments; median " << fixed(t.median * 1e3, 3) << " ms (" << fixed(t.min * 1e3, 3) << " .. "
        << fixed(t.max * 1e3, 3) << "), " << fixed(1 / t.median, 1) << " frames/s, "
        << fixed(static_cast<double>(fragments) / t.median / 1e6, 1) << " Mfragments/s\n"
        << "each CPU alone after these frames (a cache-resident loop on one pinned thread): " << describe_cpu_speeds(cpu_speeds(3))
        << "\n";
    if (threads > 1)
      out << "serial part (this thread outside the pool's runs): median " << fixed(row.serial.median * 1e3, 3)
          << " ms of each frame; with one thread's frame time T1 the speed-up is at most T1 / (serial + (T1 - serial) / "
          << threads << ") (docs/performance.md 31)\n"
          << "parallel ceiling of this machine just before these frames (a cache-resident loop per thread): "
          << fixed(ceiling, 2) << "x; the machine bound is T1 / (serial + (T1 - serial) / " << fixed(machine_speed(threads, ceiling), 2)
          << ") (docs/performance.md 33)\n";
  } catch (const trace::TraceError& e) {
    err << "ffsim bench --perf: " << e.what() << "\n";
    return 1;
  } catch (const std::exception& e) {
    err << "ffsim bench --perf: " << e.what() << "\n";
    return 1;
  }
  return 0;
}

}  // namespace

std::string perf_usage() {
  return "usage: ffsim bench --perf [--quick] [--only stages|traces|scaling|threads] [--repeat N]\n"
         "                          [--size N] [--threads 1,2,...] [--traces DIR] [--out DIR]\n"
         "       ffsim bench --perf --trace FILE [--set NAME=EXPR ...] [--repeat N] [--threads N[,M...]]\n\n"
         "Throughput (issue 10), each time beside its memory-bandwidth floor (the bytes the pass\n"
         "must read and write / this machine's measured copy bandwidth):\n"
         "  stages   Mfragments/s of one pass on one core, N x N window (--size, default 1024;\n"
         "           set-ups in traces/perf/)\n"
         "  traces   frames/s of kautz-imaging-hard, kautz-imaging-aa, kautz-geforce-aa on the\n"
         "           polygon at 512^2 and the terrain at 640x480, one thread\n"
         "  scaling  frames/s of the same traces at 256^2, 512^2, 1024^2, 2048^2\n"
         "  threads  frames/s of the terrain at 640x480 and 1280x960 and the polygon at 1024^2\n"
         "           for 1 .. hardware threads, each speed-up against one thread, and the machine's\n"
         "           parallel ceiling (a cache-resident loop per thread, all at once) before\n"
         "           and after the table; for each threaded row its serial part (the calling\n"
         "           thread outside the pool's runs), Amdahl's bound from it, the ceiling\n"
         "           measured just before the row and the machine bound (Amdahl's with the\n"
         "           split part at that ceiling)\n"
         "Median of --repeat N runs (default 7; 3 with --quick) after one warm-up, with min and max.\n"
         "--quick: 256^2 stages, the smaller sizes, about a minute. Writes perf_stages.csv,\n"
         "perf_traces.csv, perf_scaling.csv, perf_threads.csv, perf_threads_serial.csv and\n"
         "perf.md into --out\n"
         "(default docs/results). Never fails on a number.\n"
         "--trace FILE: replay one trace --repeat times (loaded once, outputs off) and print its\n"
         "median frame time, frames/s and Mfragments/s (with --threads N > 1 also the median serial\n"
         "part: the time this thread spent outside the pool's runs, and this machine's parallel ceiling\n"
         "measured just before the frames). With a list (--threads 1,2) the frames of each count run\n"
         "back to back, one count after the other, and each count's median is printed with its\n"
         "speed-up against the first count (with a first count of 1 also Amdahl's bound, the machine's\n"
         "ceiling and the machine bound, and each threaded frame taken apart: the same frames with\n"
         "every split task on the calling thread give the split work's cost on one core, and the\n"
         "frame is its serial part + the split work at the speed it reached (printed beside the\n"
         "machine's ceiling) + the caller's waits for the other threads' last tasks; then the pool's\n"
         "runs a frame, with how long after each began another thread took its first task, a late\n"
         "start, against the caller's wait for the last, a long tail: means over a frame's runs).\n"
         "Without --threads, one thread.\n";
}

namespace {
// one_thread_s / (serial_s + split / speed), split = one_thread_s - serial_s (>= 0).
double split_bound(double one_thread_s, double serial_s, double speed) {
  if (!(one_thread_s > 0) || !(speed >= 1) || !(serial_s >= 0)) return 0;
  const double split = std::max(0.0, one_thread_s - serial_s);
  const double t = serial_s + split / speed;
  return t > 0 ? one_thread_s / t : 0;
}
}  // namespace

double amdahl_bound(double one_thread_s, double serial_s, int threads) {
  return split_bound(one_thread_s, serial_s, threads);
}

ThreadedFrameParts threaded_frame_parts(double frame_s, double serial_s, double wait_s, double on_caller_s,
                                        double on_caller_serial_s) {
  ThreadedFrameParts p;
  if (!(frame_s > 0) || !(on_caller_s > 0) || !(serial_s >= 0) || !(wait_s >= 0) || !(on_caller_serial_s >= 0)) return p;
  const double split_time = frame_s - serial_s - wait_s;
  if (!(split_time > 0) || !std::isfinite(frame_s) || !std::isfinite(on_caller_s)) return p;
  p.split_work_s = std::max(0.0, on_caller_s - on_caller_serial_s);
  p.split_time_s = split_time;
  p.speed = p.split_work_s / split_time;
  return p;
}

double machine_bound(double one_thread_s, double serial_s, int threads, double ceiling) {
  if (threads < 1 || !(ceiling > 0)) return 0;
  return split_bound(one_thread_s, serial_s, machine_speed(threads, ceiling));
}

int run_perf(const std::vector<std::string>& args, std::ostream& out, std::ostream& err) {
  Options o;
  if (const int rc = parse_args(args, o, err)) return rc;
  const bool repeat_given = std::find(args.begin(), args.end(), "--repeat") != args.end();
  if (o.quick && !repeat_given) o.repeat = 3;
  const int hw = std::max(1u, std::thread::hardware_concurrency());
  // The threads table's counts by default (--trace alone times one thread).
  if (o.thread_counts.empty() && o.trace_file.empty())
    for (int t = 1; t <= std::max(2, hw); ++t) o.thread_counts.push_back(t);
  std::error_code ec;
  fs::create_directories(o.out_dir, ec);
  if (ec) {
    err << "ffsim bench --perf: cannot create `" << o.out_dir << "`: " << ec.message() << "\n";
    return 1;
  }
  if (!o.trace_file.empty()) return time_one_trace(o, out, err);
  std::ostringstream md;
  std::vector<TraceRow> rows, thread_rows;
  try {
    const double bw = copy_bandwidth(std::size_t{o.quick ? 32u : 128u} << 20, 7);
    const std::string cpus = describe_cpu_speeds(cpu_speeds(3));
    out << "copy bandwidth (read + write): " << fixed(bw / 1e9, 2) << " GB/s; hardware threads: " << hw << "\n"
        << "each CPU alone (a cache-resident loop on one pinned thread): " << cpus << "\n\n";
    md << "# Throughput (`ffsim bench --perf" << (o.quick ? " --quick" : "") << "`)\n\n"
       << "Copy bandwidth (memcpy, bytes read + written): " << fixed(bw / 1e9, 2) << " GB/s; hardware threads: " << hw
       << ". Each CPU alone (the parallel ceiling's loop on one thread pinned there, best of 3): " << cpus
       << "; one-thread rows run on whichever CPU the system gives them (docs/performance.md 34.2). Median of "
       << o.repeat << " runs after a warm-up (min .. max in the CSV files).\n\n";

    if (o.stages) {
      const int w = o.stage_size ? o.stage_size : o.quick ? 256 : 1024;
      Csv csv(fs::path(o.out_dir) / "perf_stages.csv",
              "stage,window,fragments_per_pass,median_s,min_s,max_s,mfrag_per_s,bytes_per_fragment,floor_mfrag_per_s,"
              "fraction_of_floor");
      out << "Per-stage throughput, one core, " << w << "x" << w << " window\n"
          << cell("stage", 48) << cell("Mfrag/s", 10) << cell("floor", 10) << "bytes/fragment\n";
      md << "## Per-stage throughput, one core, " << w << "x" << w << "\n\n"
         << "| stage | Mfragments/s | spread (min..max) | floor (Mfragments/s) | bytes per fragment |\n| --- | --- | --- | --- | --- |\n";
      for (const Stage& st : stages()) {
        const StageRow r = run_stage(o, st, w, o.repeat);
        const double rate = r.fragments / r.t.median / 1e6, floor = bw / st.bytes / 1e6;
        out << cell(st.name, 48) << cell(fixed(rate, 1), 10) << cell(fixed(floor, 0), 10) << st.bytes_note << "\n";
        md << "| " << st.name << " | " << fixed(rate, 1) << " | " << fixed(r.fragments / r.t.max / 1e6, 1) << " .. "
           << fixed(r.fragments / r.t.min / 1e6, 1) << " | " << fixed(floor, 0) << " | " << st.bytes_note << " |\n";
        csv.f << '"' << st.name << "\"," << w << "," << r.fragments << "," << r.t.median << "," << r.t.min << "," << r.t.max
              << "," << rate << "," << st.bytes << "," << floor << "," << rate / floor << "\n";
      }
      out << "\n";
      md << "\n";
    }

    const std::vector<std::string> traces = {"kautz-imaging-hard", "kautz-imaging-aa", "kautz-geforce-aa"};
    auto frame_line = [&](const TraceRow& r, Csv& csv, const std::string& table) {
      const double fps = 1.0 / r.t.median, floor = bw / (r.fragments * kTraceBytesPerFragment);
      out << cell(r.c.trace, 22) << cell(r.c.scene, 9) << cell(window_name(r.c), 11)
          << cell(std::to_string(r.c.threads), 8) << cell(fixed(fps, 1), 10) << cell(fixed(r.fragments / 1e6, 2), 10)
          << cell(fixed(r.fragments * fps / 1e6, 1), 10) << fixed(floor, 0) << "\n";
      md << "| " << r.c.trace << " | " << r.c.scene << " | " << window_name(r.c) << " | " << r.c.threads << " | "
         << fixed(fps, 1) << " | " << fixed(1.0 / r.t.max, 1) << " .. " << fixed(1.0 / r.t.min, 1) << " | " << r.passes << " | "
         << fixed(r.fragments / 1e6, 2) << " | " << fixed(r.fragments * fps / 1e6, 1) << " | " << fixed(floor, 0) << " |\n";
      csv.f << table << "," << r.c.trace << "," << r.c.scene << "," << r.c.width << "," << r.c.height << "," << r.c.threads << ","
            << r.passes << "," << r.fragments << "," << r.t.median << "," << r.t.min << "," << r.t.max << "," << fps << ","
            << r.fragments * fps / 1e6 << "," << floor << "\n";
    };
    const std::string csv_header =
        "table,trace,scene,width,height,threads,passes,fragments_per_frame,median_s,min_s,max_s,fps,mfrag_per_s,floor_fps";
    auto table_head = [&](const std::string& title) {
      out << title << "\n"
          << cell("trace", 22) << cell("scene", 9) << cell("window", 11) << cell("threads", 8) << cell("frames/s", 10)
          << cell("Mfrag", 10) << cell("Mfrag/s", 10) << "floor fps\n";
      md << "## " << title << "\n\n| trace | scene | window | threads | frames/s | spread | passes | Mfragments per frame | "
            "Mfragments/s | floor (frames/s) |\n| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |\n";
    };
    const std::string floor_note = "Floor: " + fixed(kTraceBytesPerFragment, 0) +
                                   " B per fragment (every pass reads the 4-byte depth and writes at least the stencil "
                                   "byte or one 2-byte colour channel) at the copy bandwidth.\n\n";

    if (o.traces) {
      Csv csv(fs::path(o.out_dir) / "perf_traces.csv", csv_header);
      table_head("Whole traces, one thread");
      for (const std::string& t : traces) {
        frame_line(run_trace_case(o, {t, "polygon", o.quick ? 256 : 512, o.quick ? 256 : 512, 1}, o.repeat), csv, "traces");
        frame_line(run_trace_case(o, {t, "terrain", o.quick ? 320 : 640, o.quick ? 240 : 480, 1}, o.repeat), csv, "traces");
      }
      out << "\n";
      md << "\n" << floor_note;
    }
    if (o.scaling) {
      Csv csv(fs::path(o.out_dir) / "perf_scaling.csv", csv_header);
      table_head("Scaling with the window size, one thread");
      const std::vector<int> sizes = o.quick ? std::vector<int>{128, 256} : std::vector<int>{256, 512, 1024, 2048};
      for (const std::string& t : traces)
        for (const char* scene : {"polygon", "terrain"})
          for (int s : sizes) {
            rows.push_back(run_trace_case(o, {t, scene, s, s, 1}, s >= 2048 ? std::max(1, o.repeat / 2) : o.repeat));
            frame_line(rows.back(), csv, "scaling");
          }
      out << "\n";
      md << "\n" << floor_note;
      const std::string svg = "perf_scaling.svg";
      write_svg((fs::path(o.out_dir) / svg).string(), scaling_plot(rows, false));
      md << "![frames per second against pixels](" << svg << ")\n\n";
    }
    if (o.threads) {
      Csv csv(fs::path(o.out_dir) / "perf_threads.csv", csv_header);
      // The machine's ceiling first (docs/performance.md 24.3), measured now: the
      // speed of a virtual machine's cores changes from minute to minute.
      auto ceilings = [&] {
        std::string c;
        for (int n : o.thread_counts)
          if (n > 1) c += (c.empty() ? "" : ", ") + std::to_string(n) + " threads " + fixed(parallel_ceiling(n, 5), 2) + "x";
        return c;
      };
      const std::string ceiling_before = ceilings();
      table_head("Scaling with worker threads (`--threads`)");
      // The terrain at 640x480 (small triangles; on two threads about a fifth of
      // the frame is serial, docs/performance.md 31) and at twice that in each
      // direction (the same serial work beside four times the pixels, 37), and the
      // polygon at 1024^2 (two large triangles: split into row bands).
      struct Window {
        const char* scene;
        int w, h;
      };
      const std::vector<Window> windows =
          o.quick ? std::vector<Window>{{"terrain", 160, 120}, {"terrain", 320, 240}, {"polygon", 256, 256}}
                  : std::vector<Window>{{"terrain", 640, 480}, {"terrain", 1280, 960}, {"polygon", 1024, 1024}};
      for (const std::string& t : traces)
        for (const Window& win : windows)
          for (int n : o.thread_counts) {
            // The machine's ceiling for this row, just before it (its speed changes
            // from minute to minute): the row's machine bound reads against it.
            const double ceiling = n > 1 ? parallel_ceiling(n, 3) : 0;
            thread_rows.push_back(run_trace_case(o, {t, win.scene, win.w, win.h, n}, o.repeat));
            thread_rows.back().ceiling = ceiling;
            frame_line(thread_rows.back(), csv, "threads");
          }
      // Speed-ups against the same trace, scene and window on one thread (this table's row).
      auto same_case = [](const TraceCase& a, const TraceCase& b) {
        return a.trace == b.trace && a.scene == b.scene && a.width == b.width && a.height == b.height;
      };
      std::string speedups;
      for (const TraceRow& r : thread_rows)
        for (const TraceRow& one : thread_rows)
          if (r.c.threads > 1 && one.c.threads == 1 && same_case(one.c, r.c))
            speedups += (speedups.empty() ? "" : ", ") + r.c.trace + " " + r.c.scene + " " + window_name(r.c) + " " +
                        std::to_string(r.c.threads) + " threads " + fixed(one.t.median / r.t.median, 2) + "x";
      if (!speedups.empty()) {
        out << "speed-up against one thread: " << speedups << "\n";
        md << "\nSpeed-up against one thread (medians): " << speedups << ".\n";
      }
      // Where each threaded frame goes: the calling thread's serial part (outside
      // the pool's runs) and the rest, and Amdahl's bound from that serial part.
      Csv split_csv(fs::path(o.out_dir) / "perf_threads_serial.csv",
                    "trace,scene,width,height,threads,median_s,serial_median_s,one_thread_median_s,speedup,amdahl_bound,"
                    "machine_ceiling,machine_bound");
      std::ostringstream split_md, split_out;
      for (const TraceRow& r : thread_rows)
        for (const TraceRow& one : thread_rows)
          if (r.c.threads > 1 && one.c.threads == 1 && same_case(one.c, r.c)) {
            const double bound = amdahl_bound(one.t.median, r.serial.median, r.c.threads);
            const double mbound = machine_bound(one.t.median, r.serial.median, r.c.threads, r.ceiling);
            const double speedup = one.t.median / r.t.median;
            split_out << "  " << cell(r.c.trace + " " + r.c.scene + " " + window_name(r.c), 42) << r.c.threads
                << " threads: serial " << fixed(r.serial.median * 1e3, 3) << " ms of " << fixed(r.t.median * 1e3, 3) << " ms, speed-up "
                << fixed(speedup, 2) << "x, Amdahl bound " << fixed(bound, 2) << "x; machine ceiling "
                << fixed(r.ceiling, 2) << "x, machine bound " << fixed(mbound, 2) << "x\n";
            split_md << "| " << r.c.trace << " | " << r.c.scene << " | " << window_name(r.c) << " | " << r.c.threads
                     << " | " << fixed(r.t.median * 1e3, 3) << " | " << fixed(r.serial.median * 1e3, 3) << " | " << fixed(100 * r.serial.median / r.t.median, 0)
                     << " % | " << fixed(speedup, 2) << "x | " << fixed(bound, 2) << "x | " << fixed(r.ceiling, 2) << "x | "
                     << fixed(mbound, 2) << "x |\n";
            split_csv.f << r.c.trace << "," << r.c.scene << "," << r.c.width << "," << r.c.height << "," << r.c.threads << ","
                        << r.t.median << "," << r.serial.median << "," << one.t.median << "," << speedup << "," << bound << ","
                        << r.ceiling << "," << mbound << "\n";
          }
      if (!split_out.str().empty())
        out << "serial part (the calling thread outside the pool's runs), Amdahl's bound from it, the machine's ceiling "
                  "just before the row and the bound with the rest split at that ceiling:\n" << split_out.str();
      if (!split_md.str().empty())
        md << "\nWhere each threaded frame goes (medians; serial: the calling thread outside the pool's runs, "
              "`Context::pool_seconds`; Amdahl bound: one thread's frame / (serial + the rest / threads), "
              "docs/performance.md 31; machine ceiling: this machine's speed-up for a cache-resident loop per "
              "thread, measured just before the row; machine bound: Amdahl's with the rest / that ceiling, "
              "docs/performance.md 33):\n\n| trace | scene | window | threads | frame ms | serial ms | serial share | speed-up | "
              "Amdahl bound | machine ceiling | machine bound |\n| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |\n"
           << split_md.str();
      if (!ceiling_before.empty()) {
        const std::string ceiling_after = ceilings();
        out << "parallel ceiling of this machine (a cache-resident loop per thread, all at once, against one), "
               "before / after this table: "
            << ceiling_before << " / " << ceiling_after << "\n";
        md << "\nParallel ceiling of this machine, measured just before / after this table (a cache-resident loop "
              "per thread, all threads at once, against one thread; docs/performance.md 24.3): "
           << ceiling_before << " / " << ceiling_after << ".\n";
      }
      out << "\n";
      md << "\n" << floor_note;
      const std::string svg = "perf_threads.svg";
      write_svg((fs::path(o.out_dir) / svg).string(), scaling_plot(thread_rows, true));
      md << "![frames per second against threads](" << svg << ")\n\n";
    }
  } catch (const std::exception& e) {
    err << "ffsim bench --perf: " << e.what() << "\n";
    return 1;
  }
  std::ofstream(fs::path(o.out_dir) / "perf.md") << md.str();
  out << "wrote " << (fs::path(o.out_dir) / "perf.md").string() << " and perf_*.csv\n";
  return 0;
}

}  // namespace ffsim::bench
