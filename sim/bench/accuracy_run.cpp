#include "sim/bench/accuracy_run.h"

#include <chrono>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <map>
#include <memory>
#include <ostream>
#include <tuple>

#include "bumpshadow/cache.h"
#include "bumpshadow/ellipse_test.h"
#include "bumpshadow/generators.h"
#include "bumpshadow/reference.h"
#include "sim/bench/pareto.h"
#include "sim/trace/error.h"

namespace ffsim::bench {

namespace fs = std::filesystem;
using Sets = std::vector<std::pair<std::string, std::string>>;

double AccuracyRow::mean_disagreement() const {
  return acc.lights ? acc.sum_dis / acc.lights : std::numeric_limits<double>::quiet_NaN();
}

Spread AccuracyRow::time_ms() const {
  Spread s = spread(acc.seconds);
  return {s.median * 1e3, s.min * 1e3, s.max * 1e3};
}

void mark_pareto(std::vector<AccuracyRow>& rows) {
  std::map<std::pair<std::string, int>, std::vector<std::size_t>> groups;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    rows[i].pareto = false;
    if (rows[i].acc.ok && rows[i].acc.lights > 0 && !rows[i].acc.seconds.empty())
      groups[{rows[i].scene, rows[i].size}].push_back(i);
  }
  for (const auto& [key, idx] : groups) {
    std::vector<std::pair<double, double>> pts;
    for (std::size_t i : idx) pts.push_back({rows[i].time_ms().median, rows[i].mean_disagreement()});
    for (std::size_t k : pareto_front(pts)) rows[idx[k]].pareto = true;
  }
}

namespace {

double now() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

std::string num17(double v) {
  char b[40];
  std::snprintf(b, sizeof b, "%.17g", v);
  return b;
}

// The scene's height field exactly as include/scene.trace asks the generators for it
// (field, seed and scale), for timing the CPU paths.
bumpshadow::HeightField scene_field(int scene, int res) {
  const std::string w = std::to_string(res);
  if (scene == 0) return bumpshadow::generate("bumps", {{"w", w}, {"seed", "1"}});
  return bumpshadow::generate("fractal", {{"w", w}, {"seed", "7"}}).scaled(res / 32.0);
}

// Loads a trace; nullptr and `error` on failure.
std::unique_ptr<trace::Program> load(const std::string& path, const Sets& sets, const std::string& profile, std::string& error) {
  try {
    trace::LoadOptions lo;
    lo.sets = sets;
    lo.profile = profile;
    return std::make_unique<trace::Program>(trace::load_trace_file(path, lo));
  } catch (const trace::TraceError& e) {
    error = e.where().str() + ": " + e.what();
  } catch (const std::exception& e) {
    error = e.what();
  }
  return nullptr;
}

template <class F>
std::vector<double> time_runs(int n, F&& f) {
  std::vector<double> t;
  for (int k = 0; k < n; ++k) {
    const double t0 = now();
    f();
    t.push_back(now() - t0);
  }
  return t;
}

}  // namespace

AccuracyResult run_accuracy_config(const AccuracyConfig& c, std::ostream& progress) {
  AccuracyResult result;
  const double start = now();
  // Profiles in run order: ideal first (the other profiles are compared with it).
  std::vector<std::string> profiles = {"ideal"};
  for (const auto& p : c.profiles)
    if (p != "ideal") profiles.push_back(p);
  const std::string ref_path = (fs::path(c.traces_dir) / "kautz-reference.trace").string();
  const std::string bump_path = (fs::path(c.traces_dir) / "bump-only.trace").string();

  for (const SceneSpec& sc : c.scenes)
    for (int size : c.sizes) {
      Sets base = {{"scene", std::to_string(sc.scene)}, {"res", std::to_string(c.map_res)}, {"rays", std::to_string(c.rays)}};
      if (sc.scene == 0) base.push_back({"zoom", std::to_string(size / c.map_res)});
      else base.push_back({"tw", std::to_string(size)}), base.push_back({"th", std::to_string(size)});

      // The rows of this (scene, size).
      const std::size_t first = result.rows.size();
      std::map<std::tuple<std::size_t, std::string, int>, std::size_t> at;
      for (std::size_t v = 0; v < c.variants.size(); ++v) {
        const VariantSpec& spec = c.variants[v];
        const bool cpu = spec.kind == VariantKind::Ellipse || spec.kind == VariantKind::Reference;
        for (const auto& p : cpu ? std::vector<std::string>{"float64"} : profiles)
          for (int f : cpu ? std::vector<int>{-1} : c.filters) {
            AccuracyRow row;
            row.scene = sc.name;
            row.size = size;
            row.variant = spec;
            row.profile = p;
            row.filter = f;
            at[{v, p, f}] = result.rows.size();
            result.rows.push_back(std::move(row));
          }
      }
      auto fail_all = [&](const std::string& m) {
        for (std::size_t i = first; i < result.rows.size(); ++i) result.rows[i].acc.fail(m);
      };

      // Light-independent inputs of the CPU rows' timing.
      bool need_cpu = false;
      for (const auto& v : c.variants) need_cpu = need_cpu || v.kind == VariantKind::Ellipse || v.kind == VariantKind::Reference;
      std::unique_ptr<bumpshadow::HeightField> field;
      std::unique_ptr<bumpshadow::EllipseMap> ellipses;
      double shade_seconds = 0;  // median replay of bump-only.trace: the shading pass the CPU paths still need
      if (need_cpu) {
        try {
          field = std::make_unique<bumpshadow::HeightField>(scene_field(sc.scene, c.map_res));
          bumpshadow::ShadowMapOptions o;
          o.rays = bumpshadow::rays_for_count(c.rays);
          o.rays.seed = 1;
          ellipses = std::make_unique<bumpshadow::EllipseMap>(bumpshadow::cached_ellipse_map(*field, o, "out/cache"));
          std::string error;
          Sets s = base;
          s.push_back({"lx", "0.5"}), s.push_back({"ly", "0.5"});
          auto prog = load(bump_path, s, "ideal", error);
          if (!prog) throw std::runtime_error(bump_path + ": " + error);
          paper::replay(*prog, "", c.threads, false);
          shade_seconds = spread(time_runs(c.repeat, [&] { paper::replay(*prog, "", c.threads, false); })).median;
        } catch (const std::exception& e) {
          fail_all(std::string("CPU timing set-up: ") + e.what());
        }
      }

      for (std::size_t li = 0; li < c.lights.size(); ++li) {
        const Light& light = c.lights[li];
        const double t_light = now();
        int runs = 0;
        Sets lsets = base;
        lsets.push_back({"lx", num17(light.lx())});
        lsets.push_back({"ly", num17(light.ly())});
        Sets rsets = lsets;
        rsets.push_back({"filter", "1"});
        const paper::Run ref = paper::run_trace(ref_path, rsets, "", c.threads, "ideal");
        ++runs;
        if (!ref.ok) {
          fail_all("reference " + light.label() + ": " + ref.error);
          continue;
        }
        ReferenceFrame rf;
        try {
          rf = reference_frame(ref);
        } catch (const std::exception& e) {
          fail_all("reference " + light.label() + ": " + e.what());
          continue;
        }
        const bumpshadow::Vec3 L{light.lx(), light.ly(), std::sqrt(std::max(0.0, 1 - light.lx() * light.lx() - light.ly() * light.ly()))};

        for (std::size_t v = 0; v < c.variants.size(); ++v) {
          const VariantSpec& spec = c.variants[v];
          if (spec.kind == VariantKind::Ellipse || spec.kind == VariantKind::Reference) {
            AccuracyRow& row = result.rows[at.at({v, "float64", -1})];
            const Frame& f = spec.kind == VariantKind::Ellipse ? rf.ellipse : rf.exact;
            row.acc.add(frame_error(f, rf.exact, rf.covered, &rf.soft), light.label());
            if (li == 0 && field && ellipses) {
              // Per frame on the CPU: the light-dependent map (one thread), then one shading pass.
              std::vector<double> t = spec.kind == VariantKind::Reference
                                          ? time_runs(c.repeat, [&] { (void)bumpshadow::reference_lit_map(*field, L, {}, 1); })
                                          : time_runs(c.repeat, [&] { (void)bumpshadow::ellipse_test_map(*ellipses, L); });
              for (double& x : t) x += shade_seconds;
              row.acc.seconds = t;
            }
            continue;
          }
          const std::string path = (fs::path(c.traces_dir) / (spec.trace + ".trace")).string();
          for (int f : c.filters) {
            Frame ideal;
            bool have_ideal = false;
            for (const auto& p : profiles) {
              AccuracyRow& row = result.rows[at.at({v, p, f})];
              Sets s = lsets;
              s.push_back({"filter", std::to_string(f)});
              for (const auto& kv : spec.sets) s.push_back(kv);
              std::string error;
              auto prog = load(path, s, p, error);
              if (!prog) {
                row.acc.fail(light.label() + ": " + error);
                continue;
              }
              const paper::Run run = paper::replay(*prog, "", c.threads);  // warm-up; its dumps give the errors
              ++runs;
              if (!run.ok) {
                row.acc.fail(light.label() + ": " + run.error);
                continue;
              }
              Frame frame;
              try {
                frame = variant_frame(run, spec.kind);
              } catch (const std::exception& e) {
                row.acc.fail(light.label() + ": " + e.what());
                continue;
              }
              row.acc.add(frame_error(frame, rf.exact, rf.covered, &rf.soft), light.label());
              if (p == "ideal") {
                ideal = std::move(frame);
                have_ideal = true;
              } else if (have_ideal) {
                row.acc.add_vs_ideal(frame_error(frame, ideal, rf.covered, nullptr));
              }
              if (li == 0) {
                row.acc.seconds = time_runs(c.repeat, [&] { paper::replay(*prog, "", c.threads, false); });
                runs += c.repeat;
              }
            }
          }
        }
        char buf[200];
        std::snprintf(buf, sizeof buf, "[%s %dx%d] light %zu/%zu %s: %d replays, %.1f s (total %.0f s)\n", sc.name.c_str(), size, size,
                      li + 1, c.lights.size(), light.label().c_str(), runs, now() - t_light, now() - start);
        progress << buf << std::flush;
      }
    }
  for (const auto& r : result.rows) result.all_ok = result.all_ok && r.acc.ok;
  mark_pareto(result.rows);
  result.seconds = now() - start;
  return result;
}

}  // namespace ffsim::bench
