// `ffsim bumpshadow`: precomputes the ellipse shadow map of a height field (file
// or named generator) and writes every map of the paper's sections 4.1 and 5.1,
// a normal map and Max's horizon map, plus a text and JSON report.
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <optional>
#include <sstream>

#include "bumpshadow/cache.h"
#include "bumpshadow/ellipse_test.h"
#include "bumpshadow/encodings.h"
#include "bumpshadow/generators.h"
#include "bumpshadow/reference.h"
#include "sim/cli/cli.h"
#include "sim/heightfield_io.h"

namespace ffsim::cli {

namespace bs = ffsim::bumpshadow;

namespace {

const char* kUsage =
    "usage: ffsim bumpshadow HEIGHTFIELD|--generate NAME [k=v...] [options]\n\n"
    "Precomputes the ellipse shadow map (Kautz, Heidrich, Daubert 2000, section 2) of a\n"
    "height field and writes, into --out DIR, each map as float EXR (exact, unclamped)\n"
    "and 8-bit PNG (clamped, rounded half up):\n"
    "  t1r, t2r (RGBA, biased, alpha 1), t3r (alpha = rx^2/2)        section 4.1\n"
    "  t1n (RGBA, biased, alpha = rx^2), t2n (RGBA, biased, alpha 1)  section 5.1\n"
    "  normal (RGB biased, dot-product bump mapping), heights.exr,\n"
    "  horizon-G.exr (Max's horizon angles in radians, azimuths 4G..4G+3),\n"
    "  report.txt and report.json (degenerate texels, agreement, range violations).\n\n"
    "HEIGHTFIELD is an 8/16-bit PNG or TIFF or an EXR (channel 0, value in [0,1] for\n"
    "integer files, times --scale = height in texels).\n\n"
    "options:\n"
    "  --generate NAME [k=v...]  a named generator instead of a file (--list shows them)\n"
    "  --list                    list the generators and their parameters\n"
    "  --scale S                 height scale (default 1; for files: height of value 1)\n"
    "  --border wrap|clamp       border rule of a loaded file (default wrap)\n"
    "  --rays N                  rays per texel, rounded to k^2 with k = round(sqrt N) (default 256)\n"
    "  --horizon N               azimuths of the horizon map (default 8; 0 = none)\n"
    "  --max-distance D          march cut-off in texels (default: the larger side)\n"
    "  --light X,Y,Z             also evaluate a directional light (tangent frame, z up;\n"
    "                            repeatable): writes reference-N.png (exact ray-cast\n"
    "                            lit map) and reports the fraction of texels the float64\n"
    "                            ellipse test and the horizon map get wrong\n"
    "  --threads N               worker threads (default: all; results do not depend on it)\n"
    "  --out DIR                 output directory (default out/bumpshadow)\n"
    "  --cache DIR               cache directory (default DIR/cache)\n"
    "  --no-cache                neither read nor write the cache\n";

bool parse_int(const std::string& s, int& v, int lo, int hi) {
  try {
    std::size_t used = 0;
    const long long x = std::stoll(s, &used);
    if (used != s.size() || x < lo || x > hi) return false;
    v = static_cast<int>(x);
    return true;
  } catch (const std::exception&) {
    return false;
  }
}

std::string json_escape(const std::string& s) {
  std::string o;
  for (char c : s) {
    if (c == '"' || c == '\\') o += '\\';
    if (static_cast<unsigned char>(c) < 0x20) {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\u%04x", c);
      o += buf;
      continue;
    }
    o += c;
  }
  return o;
}

// A one-line progress bar on a terminal; nothing otherwise.
class ProgressBar {
 public:
  ProgressBar(std::ostream& err, std::string label)
      : on_(&err == &std::cerr && ::isatty(STDERR_FILENO)), err_(err), label_(std::move(label)) {}
  void operator()(int done, int total) {
    if (!on_) return;
    const int width = 40, fill = total > 0 ? done * width / total : width;
    err_ << "\r" << label_ << " [" << std::string(fill, '#') << std::string(width - fill, ' ') << "] " << done << "/"
         << total << std::flush;
    if (done == total) err_ << "\n";
  }

 private:
  bool on_;
  std::ostream& err_;
  std::string label_;
};

}  // namespace

Subcommand bumpshadow_command() {
  Subcommand s;
  s.name = "bumpshadow";
  s.summary = "precompute ellipse shadow maps, encodings and horizon maps of a height field";
  s.usage = kUsage;
  s.run = [](const std::vector<std::string>& args, std::ostream& out, std::ostream& err) {
    std::string file, gen, dir = "out/bumpshadow", cache_dir;
    std::vector<std::string> kv;
    std::vector<bs::Vec3> lights;
    double scale = 1, max_distance = 0;
    int rays = 256, threads = 0, horizon = 8;
    bool no_cache = false;
    bs::Border border = bs::Border::Wrap;
    for (std::size_t i = 0; i < args.size(); ++i) {
      const std::string& a = args[i];
      auto value = [&](const char* what) -> std::optional<std::string> {
        if (i + 1 >= args.size()) return std::nullopt;
        (void)what;
        return args[++i];
      };
      if (a == "--list") {
        for (const auto& g : bs::generators()) {
          out << g.name << ": " << g.summary << "\n";
          for (const auto& p : g.params)
            out << "    " << p.key << "=" << (p.default_value.empty() ? "(see text)" : p.default_value) << "  "
                << p.meaning << "\n";
        }
        return 0;
      } else if (a == "--generate") {
        auto v = value("name");
        if (!v) return usage_error(err, "bumpshadow", "--generate needs a generator name");
        gen = *v;
        while (i + 1 < args.size() && args[i + 1].find('=') != std::string::npos && args[i + 1][0] != '-')
          kv.push_back(args[++i]);
      } else if (a == "--scale") {
        auto v = value("S");
        char* end = nullptr;
        if (v) scale = std::strtod(v->c_str(), &end);
        if (!v || end == v->c_str() || *end != '\0' || !std::isfinite(scale) || scale <= 0)
          return usage_error(err, "bumpshadow", "--scale expects a finite number > 0");
      } else if (a == "--border") {
        auto v = value("rule");
        if (v && *v == "wrap") border = bs::Border::Wrap;
        else if (v && *v == "clamp") border = bs::Border::Clamp;
        else return usage_error(err, "bumpshadow", "--border expects wrap or clamp");
      } else if (a == "--max-distance") {
        auto v = value("D");
        char* end = nullptr;
        if (v) max_distance = std::strtod(v->c_str(), &end);
        if (!v || end == v->c_str() || *end != '\0' || !std::isfinite(max_distance) || max_distance <= 0)
          return usage_error(err, "bumpshadow", "--max-distance expects a finite number > 0");
      } else if (a == "--light") {
        auto v = value("X,Y,Z");
        bs::Vec3 l;
        char tail = 0;
        if (!v || std::sscanf(v->c_str(), "%lf,%lf,%lf%c", &l.x, &l.y, &l.z, &tail) != 3 || !std::isfinite(l.x) ||
            !std::isfinite(l.y) || !std::isfinite(l.z) || !(l.z > 0))
          return usage_error(err, "bumpshadow", "--light expects X,Y,Z with finite numbers and Z > 0");
        lights.push_back(l);
      } else if (a == "--rays") {
        auto v = value("N");
        if (!v || !parse_int(*v, rays, 4, 1 << 20)) return usage_error(err, "bumpshadow", "--rays expects 4..1048576");
      } else if (a == "--horizon") {
        auto v = value("N");
        if (!v || !parse_int(*v, horizon, 0, 4096)) return usage_error(err, "bumpshadow", "--horizon expects 0..4096");
      } else if (a == "--threads") {
        auto v = value("N");
        if (!v || !parse_int(*v, threads, 1, 1024)) return usage_error(err, "bumpshadow", "--threads expects 1..1024");
      } else if (a == "--out") {
        auto v = value("DIR");
        if (!v) return usage_error(err, "bumpshadow", "--out needs a directory");
        dir = *v;
      } else if (a == "--cache") {
        auto v = value("DIR");
        if (!v) return usage_error(err, "bumpshadow", "--cache needs a directory");
        cache_dir = *v;
      } else if (a == "--no-cache") {
        no_cache = true;
      } else if (!a.empty() && a[0] != '-' && file.empty()) {
        file = a;
      } else {
        return usage_error(err, "bumpshadow", "unknown argument `" + a + "`");
      }
    }
    if (file.empty() == gen.empty())
      return usage_error(err, "bumpshadow", "give either a HEIGHTFIELD file or --generate NAME");
    if (cache_dir.empty()) cache_dir = dir + "/cache";
    try {
      const auto t0 = std::chrono::steady_clock::now();
      std::string source;
      std::optional<bs::HeightField> loaded;
      if (!gen.empty()) {
        const bs::GeneratorParams p = bs::parse_generator_params(kv);
        loaded.emplace(bs::generate(gen, p));
        source = bs::describe_generator(gen, p);
        if (scale != 1) loaded.emplace(loaded->scaled(scale));
      } else {
        loaded.emplace(load_heightfield(file, scale, border));
        source = file;
      }
      const bs::HeightField& hf = *loaded;
      bs::ShadowMapOptions o;
      o.rays = bs::rays_for_count(rays);
      o.rays.march.max_distance = max_distance;
      o.threads = threads;
      ProgressBar bar(err, "ellipse fit");
      o.progress = [&bar](int d, int t) { bar(d, t); };
      bool hit = false, hhit = false;
      const bs::EllipseMap m = no_cache ? bs::compute_ellipse_map(hf, o) : bs::cached_ellipse_map(hf, o, cache_dir, &hit);
      std::optional<bs::HorizonMap> hm;
      if (horizon > 0) {
        ProgressBar hbar(err, "horizon map");
        const bs::Progress hp = [&hbar](int d, int t) { hbar(d, t); };
        hm.emplace(no_cache ? bs::compute_horizon_map(hf, horizon, o.rays.march, threads, hp)
                            : bs::cached_horizon_map(hf, horizon, o.rays.march, cache_dir, threads, hp, &hhit));
      }
      const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      const bs::EncodedMaps em = bs::encode_maps(m);
      const bs::FloatMap nm = bs::normal_map(hf);
      std::filesystem::create_directories(dir);
      const std::pair<const bs::FloatMap*, const bs::ByteMap*> maps[] = {
          {&em.t1r, &em.t1r8}, {&em.t2r, &em.t2r8}, {&em.t3r, &em.t3r8}, {&em.t1n, &em.t1n8}, {&em.t2n, &em.t2n8}};
      for (const auto& [f, b] : maps) {
        write_image(dir + "/" + f->name + ".exr", float_map_image(*f));
        write_image(dir + "/" + f->name + ".png", byte_map_image(*b));
      }
      write_image(dir + "/normal.exr", float_map_image(nm));
      write_image(dir + "/normal.png", byte_map_image(bs::quantise(nm)));
      write_image(dir + "/heights.exr", heightfield_image(hf));
      if (hm)
        for (int g = 0; g * 4 < hm->azimuths; ++g) write_image(dir + "/horizon-" + std::to_string(g) + ".exr", horizon_group_image(*hm, g));

      std::ostringstream txt, js;
      txt.precision(6);
      js.precision(9);
      txt << "source      " << source << "\n"
          << "size        " << hf.width() << "x" << hf.height() << ", border " << bs::border_name(hf.border())
          << ", scale " << scale << "\n"
          << "options     " << bs::describe_options(o) << "\n"
          << "rays        " << m.rays_per_texel << " per texel\n"
          << "cache       " << (no_cache ? "off" : hit ? "hit" : "computed") << " (" << cache_dir << ")\n"
          << "time        " << seconds << " s\n"
          << "agreement   " << m.agreement() << " of (texel, ray) pairs: ellipse test == ray cast\n"
          << "texels      ";
      js << "{\n  \"source\": \"" << json_escape(source) << "\",\n  \"width\": " << hf.width()
         << ",\n  \"height\": " << hf.height() << ",\n  \"border\": \"" << bs::border_name(hf.border())
         << "\",\n  \"scale\": " << scale << ",\n  \"options\": \"" << json_escape(bs::describe_options(o))
         << "\",\n  \"rays_per_texel\": " << m.rays_per_texel << ",\n  \"cache_hit\": " << (hit ? "true" : "false")
         << ",\n  \"agreement\": " << m.agreement() << ",\n  \"texel_kinds\": {";
      for (int k = 0; k < bs::kTexelKinds; ++k) {
        const char* name = bs::texel_kind_name(static_cast<bs::TexelKind>(k));
        txt << (k ? ", " : "") << name << " " << m.kind_count[k];
        js << (k ? ", " : "") << "\"" << name << "\": " << m.kind_count[k];
      }
      txt << "\nassumptions |C| > 1: " << em.center_outside_unit << ", rx > sqrt2: " << em.rx_above_sqrt2
          << ", rx > 1: " << em.rx_above_1 << " texels\n";
      js << "},\n  \"center_outside_unit\": " << em.center_outside_unit << ",\n  \"rx_above_sqrt2\": "
         << em.rx_above_sqrt2 << ",\n  \"rx_above_1\": " << em.rx_above_1 << ",\n  \"maps\": [";
      for (std::size_t r = 0; r < em.ranges.size(); ++r) {
        const bs::RangeReport& rr = em.ranges[r];
        txt << "map " << rr.map << ": " << rr.texels_out_of_range << " texels / " << rr.components_out_of_range
            << " components out of range before biasing, " << rr.components_clamped << " components clamped in 8 bits\n";
        js << (r ? "," : "") << "\n    {\"map\": \"" << rr.map << "\", \"texels_out_of_range\": " << rr.texels_out_of_range
           << ", \"components_out_of_range\": " << rr.components_out_of_range
           << ", \"components_clamped\": " << rr.components_clamped << "}";
      }
      js << "\n  ],\n  \"lights\": [";
      for (std::size_t li = 0; li < lights.size(); ++li) {
        const bs::Vec3& L = lights[li];
        const std::vector<std::uint8_t> ref = bs::reference_lit_map(hf, L, o.rays.march, threads);
        Image im = Image::make(hf.width(), hf.height(), 1, SampleType::U8);
        for (std::size_t t = 0; t < ref.size(); ++t) im.u8[t] = ref[t] ? 255 : 0;
        write_image(dir + "/reference-" + std::to_string(li) + ".png", im);
        const bs::ShadowErrorStats es = bs::compare_with_reference(bs::ellipse_test_map(m, L), ref);
        txt << "light " << li << "     (" << L.x << ", " << L.y << ", " << L.z << "): ellipse test wrong on "
            << es.error_fraction() << " of texels (" << es.false_lit << " false lit, " << es.false_shadow
            << " false shadow)";
        js << (li ? "," : "") << "\n    {\"light\": [" << L.x << ", " << L.y << ", " << L.z
           << "], \"ellipse_error\": " << es.error_fraction() << ", \"ellipse_false_lit\": " << es.false_lit
           << ", \"ellipse_false_shadow\": " << es.false_shadow;
        if (hm) {
          const bs::ShadowErrorStats hs = bs::compare_lit_maps(bs::horizon_lit_map(*hm, L), ref);
          txt << ", horizon map wrong on " << hs.error_fraction();
          js << ", \"horizon_error\": " << hs.error_fraction();
        }
        txt << "\n";
        js << "}";
      }
      if (hm) txt << "horizon     " << hm->azimuths << " azimuths" << (no_cache ? "" : hhit ? " (cache hit)" : "") << "\n";
      js << "\n  ],\n  \"horizon_azimuths\": " << (hm ? hm->azimuths : 0) << ",\n  \"seconds\": " << seconds << "\n}\n";
      std::ofstream(dir + "/report.txt") << txt.str();
      std::ofstream(dir + "/report.json") << js.str();
      out << txt.str() << "wrote " << dir << "/{t1r,t2r,t3r,t1n,t2n,normal}.{exr,png}, heights.exr"
          << (hm ? ", horizon-*.exr" : "") << ", report.{txt,json}\n";
      return 0;
    } catch (const std::exception& e) {
      err << "ffsim bumpshadow: " << e.what() << "\n";
      return 1;
    }
  };
  return s;
}

}  // namespace ffsim::cli
