#include "sim/bench/accuracy_config.h"

#include <cmath>
#include <cstdio>
#include <sstream>

namespace ffsim::bench {

const std::vector<VariantSpec>& all_variants() {
  static const std::vector<VariantSpec> v = {
      {"kautz-imaging-hard", "kautz-imaging-hard", VariantKind::Hard, {}, "4.1.5 imaging subset, stencil"},
      {"kautz-imaging-aa", "kautz-imaging-aa", VariantKind::AA, {}, "4.2 imaging subset, alpha"},
      {"kautz-geforce-aa", "kautz-geforce-aa", VariantKind::AA, {}, "5.2 combiners, pre-squared"},
      {"kautz-geforce-aa-unsquared", "kautz-geforce-aa-unsquared", VariantKind::AA, {}, "5.2 squaring after filtering"},
      {"kautz-geforce-hard", "kautz-geforce-hard", VariantKind::Hard, {}, "5.2 test + 4.1.5 stencil"},
      {"max-horizon-8", "max-horizon", VariantKind::Hard, {{"azimuths", "8"}}, "Max 1988, 8 azimuths"},
      {"max-horizon-16", "max-horizon", VariantKind::Hard, {{"azimuths", "16"}}, "Max 1988, 16 azimuths"},
      {"max-horizon-32", "max-horizon", VariantKind::Hard, {{"azimuths", "32"}}, "Max 1988, 32 azimuths"},
      {"float64-ellipse", "kautz-reference", VariantKind::Ellipse, {}, "ellipse test in float64 on the CPU"},
      {"reference", "kautz-reference", VariantKind::Reference, {}, "exact ray cast on the CPU"},
  };
  return v;
}

const char* kind_name(VariantKind k) {
  switch (k) {
    case VariantKind::Hard: return "hard";
    case VariantKind::AA: return "antialiased";
    case VariantKind::Ellipse: return "cpu-ellipse";
    case VariantKind::Reference: return "cpu-reference";
  }
  return "?";
}

namespace {
constexpr double kPi = 3.14159265358979323846;
}

double Light::lx() const { return std::cos(elevation_deg * kPi / 180) * std::cos(azimuth_deg * kPi / 180); }
double Light::ly() const { return std::cos(elevation_deg * kPi / 180) * std::sin(azimuth_deg * kPi / 180); }
std::string Light::label() const {
  char b[32];
  std::snprintf(b, sizeof b, "a%ge%g", azimuth_deg, elevation_deg);
  return b;
}

std::vector<Light> light_sweep() {
  std::vector<Light> v;
  for (double e : {60.0, 30.0, 15.0, 5.0})
    for (int a = 0; a < 360; a += 30) v.push_back({static_cast<double>(a), e});
  return v;
}

std::vector<Light> light_subset(int n) {
  const std::vector<Light> all = light_sweep();
  const int m = static_cast<int>(all.size());
  std::vector<Light> v;
  for (int k = 0; k < std::min(n, m); ++k) v.push_back(all[static_cast<std::size_t>((k * 13) % m)]);
  return v;
}

std::string filter_name(int filter) { return filter ? "linear" : "nearest"; }

AccuracyConfig default_config() {
  AccuracyConfig c;
  c.variants = all_variants();
  c.profiles = {"geforce256", "rgba10", "rgba12", "float32", "ideal"};
  c.filters = {0, 1};
  c.sizes = {256, 512, 1024};
  c.scenes = {{0, "polygon"}, {1, "terrain"}};
  c.lights = light_sweep();
  c.repeat = 3;
  return c;
}

AccuracyConfig quick_config() {
  AccuracyConfig c = default_config();
  c.name = "accuracy-quick";
  c.profiles = {"geforce256", "ideal"};
  c.filters = {1};
  c.sizes = {256};
  c.lights = light_subset(3);
  c.repeat = 2;
  return c;
}

namespace {

std::vector<std::string> split(const std::string& s) {
  std::vector<std::string> v;
  std::stringstream ss(s);
  std::string item;
  while (std::getline(ss, item, ','))
    if (!item.empty()) v.push_back(item);
  return v;
}

bool to_int(const std::string& s, int lo, int hi, int& out) {
  try {
    std::size_t pos = 0;
    const long v = std::stol(s, &pos);
    if (pos != s.size() || v < lo || v > hi) return false;
    out = static_cast<int>(v);
    return true;
  } catch (const std::exception&) {
    return false;
  }
}

}  // namespace

std::optional<AccuracyConfig> parse_accuracy_args(const std::vector<std::string>& args, std::string& error) {
  bool quick = false;
  for (const auto& a : args) quick = quick || a == "--quick";
  AccuracyConfig c = quick ? quick_config() : default_config();
  for (const auto& a : args) c.command_line += (c.command_line.empty() ? "" : " ") + a;
  for (std::size_t k = 0; k < args.size(); ++k) {
    const std::string& a = args[k];
    if (a == "--quick") continue;
    if (a == "--no-write") {
      c.write_files = false;
      continue;
    }
    if (k + 1 >= args.size()) {
      error = std::string("unknown option or missing value: ") + a;
      return std::nullopt;
    }
    const std::string& v = args[++k];
    auto bad = [&](const std::string& what) {
      error = a + " expects " + what + ", got `" + v + "`";
      return std::nullopt;
    };
    if (a == "--sizes") {
      c.sizes.clear();
      for (const auto& s : split(v)) {
        int n = 0;
        if (!to_int(s, 16, 4096, n)) return bad("frame sizes 16..4096 separated by commas (e.g. 256,512)");
        c.sizes.push_back(n);
      }
      if (c.sizes.empty()) return bad("at least one size");
    } else if (a == "--lights") {
      int n = 0;
      if (v == "all") c.lights = light_sweep();
      else if (to_int(v, 1, 48, n)) c.lights = light_subset(n);
      else return bad("a light count 1..48 or `all`");
    } else if (a == "--profiles") {
      c.profiles = split(v);
      if (c.profiles.empty()) return bad("profile names separated by commas");
    } else if (a == "--variants") {
      c.variants.clear();
      for (const auto& s : split(v)) {
        bool found = false;
        for (const auto& spec : all_variants())
          if (spec.name == s) c.variants.push_back(spec), found = true;
        if (!found) {
          std::string names;
          for (const auto& spec : all_variants()) names += (names.empty() ? "" : ", ") + spec.name;
          return bad("variant names from: " + names);
        }
      }
      if (c.variants.empty()) return bad("at least one variant");
    } else if (a == "--filters") {
      c.filters.clear();
      for (const auto& s : split(v)) {
        if (s == "nearest") c.filters.push_back(0);
        else if (s == "linear") c.filters.push_back(1);
        else return bad("nearest and/or linear separated by commas");
      }
      if (c.filters.empty()) return bad("nearest and/or linear");
    } else if (a == "--scenes") {
      c.scenes.clear();
      for (const auto& s : split(v)) {
        if (s == "polygon") c.scenes.push_back({0, "polygon"});
        else if (s == "terrain") c.scenes.push_back({1, "terrain"});
        else return bad("polygon and/or terrain separated by commas");
      }
      if (c.scenes.empty()) return bad("polygon and/or terrain");
    } else if (a == "--repeat") {
      if (!to_int(v, 1, 1000, c.repeat)) return bad("a repeat count 1..1000");
    } else if (a == "--threads") {
      if (!to_int(v, 0, 256, c.threads)) return bad("a thread count 0..256");
    } else if (a == "--res") {
      if (!to_int(v, 4, 1024, c.map_res)) return bad("a map resolution 4..1024");
    } else if (a == "--rays") {
      if (!to_int(v, 4, 4096, c.rays)) return bad("a ray count 4..4096");
    } else if (a == "--out") {
      c.out_dir = v;
    } else if (a == "--name") {
      if (v.empty() || v.find('/') != std::string::npos) return bad("a file stem without `/`");
      c.name = v;
    } else if (a == "--traces") {
      c.traces_dir = v;
    } else {
      error = std::string("unknown option: ") + a;
      return std::nullopt;
    }
  }
  for (int s : c.sizes)
    if (s % c.map_res != 0) {
      error = std::string("--sizes: ") + std::to_string(s) + " is not a multiple of the map resolution " +
              std::to_string(c.map_res) + " (the polygon is drawn at an integer zoom)";
      return std::nullopt;
    }
  return c;
}

}  // namespace ffsim::bench
