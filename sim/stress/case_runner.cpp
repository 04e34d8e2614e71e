#include "sim/stress/case_runner.h"

#include <cmath>
#include <cstdio>
#include <ostream>

#include "bumpshadow/reference.h"
#include "sim/stress/cases.h"
#include "sim/stress/invariants.h"
#include "sim/stress/traces.h"

namespace ffsim::stress {

namespace bs = ffsim::bumpshadow;

namespace {

const char* const kFixedProfiles[] = {"geforce256", "rgba10", "rgba12"};

std::string num(double v) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

std::string light_text(const LightDir& l) { return std::string("(") + num(l.lx) + ", " + num(l.ly) + ", " + num(l.lz) + ")"; }

int pick(bs::SplitMix64& rng, int n) { return static_cast<int>(rng.next() % static_cast<std::uint64_t>(n)); }

void path_metrics(CaseOutcome& c, const std::string& name, const PathStats& s) {
  if (s.clamp_free) {
    c.metrics.push_back({name + " err/bound", s.max_ratio, s.worst});
    c.metrics.push_back({name + " max err LSB (clamp-free)", s.max_err_lsb, ""});
  }
  c.metrics.push_back({name + " max err LSB (clamped cases, no bound)", s.max_err_clamped_lsb, ""});
  if (s.hard_violation())
    c.violations.push_back(name + ": " + std::to_string(s.nonfinite) + " NaN/Inf, " + std::to_string(s.out_of_range) +
                           std::string(" out of range, ") + std::to_string(s.bound_exceeded) + " beyond the bound; " +
                           (s.violation.empty() ? s.worst : s.violation));
}

void encoding_metrics(CaseOutcome& c, const EncodingStats& s) {
  c.metrics.push_back({"encoding eq41 8-bit err/bound", s.max_ratio41, ""});
  c.metrics.push_back({"encoding eq51 8-bit err/bound", s.max_ratio51, ""});
  if (s.hard_violation())
    c.violations.push_back(std::string("encodings: ") + std::to_string(s.nonfinite) + " NaN/Inf, " + std::to_string(s.formula_mismatch) +
                           std::string(" eq41/eq51 mismatches, ") + std::to_string(s.bound_exceeded) + " beyond the quantisation bound; " +
                           s.worst);
}

void field_metrics(CaseOutcome& c, const FieldStats& s, const std::string& what) {
  c.metrics.push_back({"field max |C| (flag > 1)", s.max_abs_center, what});
  c.metrics.push_back({"field max rx (flag > sqrt 2)", s.max_rx, what});
  if (s.hard_violation())
    c.violations.push_back(std::string("field ") + what + ": " + std::to_string(s.nonfinite) + " NaN/Inf, " +
                           std::to_string(s.out_of_range) + " out of range, " + std::to_string(s.thread_mismatch) +
                           std::string(" thread mismatches; ") + s.detail);
}

void print_path(std::ostream* v, const std::string& name, const PathStats& s) {
  if (!v) return;
  *v << "  " << name << ": " << s.cases << " cases, " << s.clamp_free << " clamp-free, max err " << s.max_err_lsb
     << " LSB (" << s.max_ratio << " of the bound), clamped max " << s.max_err_clamped_lsb << " LSB, NaN/Inf "
     << s.nonfinite << ", out of range " << s.out_of_range << ", beyond bound " << s.bound_exceeded << "\n";
  if (!s.worst.empty()) *v << "    worst: " << s.worst << "\n";
  if (!s.violation.empty()) *v << "    violation: " << s.violation << "\n";
}

void print_inputs(std::ostream* v, const std::vector<bs::Ellipse>& ell, const std::vector<LightDir>& lights) {
  if (!v) return;
  for (const LightDir& l : lights) *v << "  light " << light_text(l) << " elevation " << l.elevation_deg() << " deg\n";
  for (const bs::Ellipse& e : ell)
    *v << "  ellipse C=(" << num(e.cx) << ", " << num(e.cy) << ") a=(" << num(e.ax) << ", " << num(e.ay)
       << ") rx=" << num(e.rx) << " ry=" << num(e.ry) << "\n";
}

void ellipse_case(CaseOutcome& c, bs::SplitMix64& rng, std::ostream* v) {
  const auto ek = static_cast<EllipseKind>(pick(rng, static_cast<int>(EllipseKind::Count)));
  std::vector<bs::Ellipse> ell(24);
  for (auto& e : ell) e = make_ellipse(ek, rng);
  std::vector<LightDir> lights(6);
  for (auto& l : lights) l = make_light(static_cast<LightKind>(pick(rng, static_cast<int>(LightKind::Count))), rng);
  const std::string prof = kFixedProfiles[pick(rng, 3)];
  const int W = pick(rng, 2) ? 4096 : 256;
  c.summary = std::string("24 ellipses ") + ellipse_kind_name(ek) + ", 6 lights, " + prof + ", table " + std::to_string(W);
  if (v) *v << c.summary << "\n";
  print_inputs(v, ell, lights);
  const EncodingStats es = encoding_path(ell, lights, &c.ranges);
  encoding_metrics(c, es);
  const Profile& p = *find_builtin_profile(prof);
  const PathStats cs = combiner_path(ell, lights, p, &c.ranges);
  path_metrics(c, std::string("combiner ") + prof, cs);
  print_path(v, std::string("combiner ") + prof, cs);
  const PathStats ls = lookup_path(ell, lights, p, W, &c.ranges);
  path_metrics(c, std::string("lookup ") + prof + " W=" + std::to_string(W), ls);
  print_path(v, std::string("lookup ") + prof + " W=" + std::to_string(W), ls);
  if (v) *v << "  encodings: " << es.cases << " cases, eq41 8-bit max " << es.max_ratio41 << " of the bound, eq51 "
            << es.max_ratio51 << "\n  ranges: " << c.ranges.str() << "\n";
}

void light_case(CaseOutcome& c, bs::SplitMix64& rng, std::ostream* v) {
  const auto lk = static_cast<LightKind>(pick(rng, static_cast<int>(LightKind::Count)));
  std::vector<LightDir> lights(12);
  for (auto& l : lights) l = make_light(lk, rng);
  std::vector<bs::Ellipse> ell(24);
  for (auto& e : ell) e = make_ellipse(EllipseKind::Paper, rng);
  c.summary = std::string("12 lights ") + light_kind_name(lk) + ", 24 paper ellipses, 6x5 noise field";
  if (v) *v << c.summary << "\n";
  print_inputs(v, ell, lights);
  for (const LightDir& l : lights) {
    double px = 0, py = 0;
    bs::project_light({l.lx, l.ly, l.lz}, px, py);
    if (!std::isfinite(px) || !std::isfinite(py))
      c.violations.push_back(std::string("project_light gives NaN/Inf for light ") + light_text(l));
  }
  const EncodingStats es = encoding_path(ell, lights, &c.ranges);
  encoding_metrics(c, es);
  const PathStats cs = combiner_path(ell, lights, *find_builtin_profile("geforce256"), &c.ranges);
  path_metrics(c, "combiner geforce256", cs);
  print_path(v, "combiner geforce256", cs);
  const bs::HeightField hf = make_field(FieldKind::Noise, 6, 5, 3.0, bs::Border::Wrap, rng.next());
  const std::vector<LightDir> three(lights.begin(), lights.begin() + 3);
  const FieldStats fs = field_path(hf, three, 16, nullptr);
  field_metrics(c, fs, "noise 6x5 scale 3 wrap");
}

void field_case(CaseOutcome& c, bs::SplitMix64& rng, std::ostream* v) {
  static const int sizes[] = {1, 2, 3, 5, 8, 13, 16, 17};
  const auto fk = static_cast<FieldKind>(pick(rng, static_cast<int>(FieldKind::Count)));
  const int w = sizes[pick(rng, 8)], h = sizes[pick(rng, 8)];
  const int sc = pick(rng, 4);
  const double scale = sc == 0 ? 1e6 : sc == 1 ? 1e-6 : std::pow(10.0, rng.uniform(-6, 6));
  const bs::Border border = pick(rng, 2) ? bs::Border::Wrap : bs::Border::Clamp;
  const std::uint64_t fseed = rng.next();
  std::vector<LightDir> lights = {make_light(LightKind::Hemisphere, rng), make_light(LightKind::Grazing, rng)};
  const int rays = pick(rng, 2) ? 64 : 16;
  const std::string what = std::string(field_kind_name(fk)) + " " + std::to_string(w) + "x" + std::to_string(h) +
                           std::string(" scale ") + num(scale) + " " + bs::border_name(border) + " rays " + std::to_string(rays);
  c.summary = std::string("field ") + what;
  if (v) {
    *v << c.summary << "\n";
    print_inputs(v, {}, lights);
  }
  const bs::HeightField hf = make_field(fk, w, h, scale, border, fseed);
  const FieldStats fs = field_path(hf, lights, rays, &c.ranges);
  field_metrics(c, fs, what);
  if (v) *v << "  " << fs.texels << " texels, |C| > 1: " << fs.center_outside << " (max " << fs.max_abs_center
            << "), rx > sqrt 2: " << fs.rx_above_sqrt2 << " (max " << fs.max_rx << "), NaN/Inf " << fs.nonfinite
            << ", out of range " << fs.out_of_range << ", thread mismatches " << fs.thread_mismatch << "\n  ranges: "
            << c.ranges.str() << "\n";
}

void trace_case(CaseOutcome& c, bs::SplitMix64& rng, const CaseOptions& o, std::ostream* v) {
  static const char* const stems[] = {"kautz-geforce-aa", "kautz-imaging-aa", "kautz-geforce-hard", "kautz-imaging-hard"};
  static const char* const profiles[] = {"geforce256", "rgba10", "rgba12", "float32", "ideal"};
  const std::string stem = stems[pick(rng, 4)], prof = profiles[pick(rng, 5)];
  const LightKind lk = pick(rng, 3) ? LightKind::Hemisphere : pick(rng, 2) ? LightKind::Grazing : LightKind::Rim;
  const LightDir l = make_light(lk, rng);
  const int res = pick(rng, 2) ? 16 : 8;
  const Sets sets = {{"res", std::to_string(res)}, {"rays", "16"}, {"lx", num(l.lx)}, {"ly", num(l.ly)}};
  c.summary = stem + " " + prof + " res " + std::to_string(res) + " light " + light_text(l) + " (" + light_kind_name(lk) + ")";
  if (v) *v << c.summary << "\n";
  const TraceRun r1 = run_paper_trace(o.traces_dir, stem, sets, prof, 1);
  if (!r1.ok) {
    // The traces refuse lights outside the unit circle with a clear error (lz =
    // sqrt of a radicand below -1e-12, traces/include/scene.trace; a radicand
    // rounded just below 0 counts as 0); anything else is a failure.
    const bool outside = !(l.lx * l.lx + l.ly * l.ly < 1);
    if (v) *v << "  run failed: " << r1.error << "\n";
    if (!(outside || (l.lz != l.lz)) || r1.error.empty()) c.violations.push_back(std::string("trace failed: ") + r1.error);
    return;
  }
  const std::string h1 = all_hashes(r1.r);
  for (int threads : {2, 3, 1}) {
    const TraceRun rt = run_paper_trace(o.traces_dir, stem, sets, prof, threads);
    if (!rt.ok || all_hashes(rt.r) != h1)
      c.violations.push_back(std::string("hashes differ between threads 1 and ") + std::to_string(threads) +
                             (threads == 1 ? " (repeated run)" : ""));
  }
  std::string first;
  const long long bad = bad_image_values(r1.r, &first);
  if (bad) c.violations.push_back(std::to_string(bad) + " image values NaN/Inf or outside [0,1], first " + first);
  if (v) *v << "  hashes " << h1 << "\n  threads 1/2/3 and a repeat: " << (c.violations.empty() ? "identical" : "DIFFER")
            << "; images checked, " << bad << " bad values\n";
}

}  // namespace

CaseOutcome run_case(CaseKind kind, std::uint64_t seed, const CaseOptions& o, std::ostream* verbose) {
  CaseOutcome c;
  c.kind = kind;
  c.seed = seed;
  bs::SplitMix64 rng(seed);
  try {
    switch (kind) {
      case CaseKind::Ellipse: ellipse_case(c, rng, verbose); break;
      case CaseKind::Light: light_case(c, rng, verbose); break;
      case CaseKind::Field: field_case(c, rng, verbose); break;
      case CaseKind::Trace: trace_case(c, rng, o, verbose); break;
      case CaseKind::Count: break;
    }
  } catch (const std::exception& e) {
    c.violations.push_back(std::string("exception: ") + e.what());
  }
  if (verbose)
    for (const std::string& s : c.violations) *verbose << "  VIOLATION: " << s << "\n";
  return c;
}

}  // namespace ffsim::stress
