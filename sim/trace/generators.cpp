#include "sim/trace/generators.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <limits>
#include <memory>
#include <mutex>
#include <stdexcept>

#include "bumpshadow/cache.h"
#include "bumpshadow/encodings.h"
#include "bumpshadow/ellipse_test.h"
#include "bumpshadow/generators.h"
#include "bumpshadow/heightfield.h"
#include "bumpshadow/horizon.h"
#include "bumpshadow/reference.h"
#include "bumpshadow/shadow_map.h"
#include "pipeline/number/unorm.h"

namespace ffsim::trace {

double GeneratorArgs::number(const std::string& key, double fallback) {
  auto it = values_.find(key);
  if (it == values_.end()) return fallback;
  it->second.used = true;
  return Expression::parse(it->second.text, it->second.where, line_).eval(lookup_);
}

long long GeneratorArgs::integer(const std::string& key, long long fallback, long long min, long long max) {
  auto it = values_.find(key);
  if (it == values_.end()) return fallback;
  const double v = number(key, 0);
  if (v != std::floor(v))
    throw TraceError(it->second.where, std::string("`") + key + "` must be an integer, got " + format_number(v), line_);
  if (v < static_cast<double>(min) || v > static_cast<double>(max))
    throw TraceError(it->second.where, std::string("`") + key + "` must be in [" + std::to_string(min) + ", " +
                                           std::to_string(max) + "], got " + format_number(v), line_);
  return static_cast<long long>(v);
}

std::string GeneratorArgs::word(const std::string& key, const std::vector<std::string>& allowed) {
  auto it = values_.find(key);
  if (it == values_.end()) return allowed.front();
  it->second.used = true;
  for (const auto& a : allowed)
    if (a == it->second.text) return a;
  std::string list;
  for (std::size_t k = 0; k < allowed.size(); ++k)
    list += (k ? (k + 1 == allowed.size() ? " or " : ", ") : "") + allowed[k];
  throw TraceError(it->second.where, std::string("`") + key + "` must be " + list + ", got `" + it->second.text + "`", line_);
}

std::pair<int, int> GeneratorArgs::size(const std::string& wkey, const std::string& hkey, int fallback) {
  const long long w = integer(wkey, fallback, 1, 16384), h = integer(hkey, fallback, 1, 16384);
  if (w * h > max_pixels_) {
    auto it = values_.find(wkey);
    const SourceLoc where = it != values_.end() ? it->second.where : SourceLoc{};
    throw TraceError(where, std::string("image size ") + std::to_string(w) + "x" + std::to_string(h) + " exceeds the limit of " +
                                std::to_string(max_pixels_) + " pixels", line_);
  }
  return {static_cast<int>(w), static_cast<int>(h)};
}

std::string GeneratorArgs::text(const std::string& key, const std::string& fallback) {
  auto it = values_.find(key);
  if (it == values_.end()) return fallback;
  it->second.used = true;
  return it->second.text;
}

SourceLoc GeneratorArgs::where(const std::string& key) const {
  auto it = values_.find(key);
  return it == values_.end() ? SourceLoc{} : it->second.where;
}

void GeneratorArgs::finish() const {
  for (const auto& [k, v] : values_)
    if (!v.used) {
      SourceLoc at = v.where;
      at.column -= static_cast<int>(k.size()) + 1;  // point at the key
      throw TraceError(at, std::string("unknown key `") + k + "`", line_);
    }
}

namespace {

Image heightfield_image(const bumpshadow::HeightField& h) {
  Image im = Image::make(h.width(), h.height(), 1, SampleType::F32);
  for (int y = 0; y < h.height(); ++y)
    for (int x = 0; x < h.width(); ++x) {
      const double v = h.at(x, y);
      if (!(std::fabs(v) <= static_cast<double>(std::numeric_limits<float>::max())))
        throw std::runtime_error(std::string("height ") + format_number(v) + " at (" + std::to_string(x) + ", " + std::to_string(y) +
                                 ") is outside the binary32 range");
      im.f32[im.index(x, y, 0)] = static_cast<float>(v);
    }
  return im;
}


// ---- [issue 8] the paper's maps from the bumpshadow generators ----
//
// Height fields: `generate H fractal w=128 seed=7 scale=1` (every bumpshadow
// generator under its own name, all its keys, plus `scale`, a factor on the
// heights) gives a 1-channel float image of heights in texel units.
//
// Maps: `generate T1r shadowmap field=bumps w=64 rays=256 map=t1r` runs the
// ellipse fit of bumpshadow on the field and returns one of the paper's maps in
// exactly the 8-bit codes bumpshadow::encode_maps quantises (rows bottom to top):
//   t1r, t2r  RGBA  biased T1^r / T2^r, alpha 1           (section 4.1.1-4.1.2)
//   t3r       1 ch  r_x^2 / 2 (upload as GL_ALPHA)          (4.1.2)
//   t1n       RGBA  biased T1^n, alpha r_x^2               (5.1.1)
//   t2n       RGBA  biased T2^n, alpha 1                   (5.1.2)
//   normal    RGB   biased unit normal (central differences) for dot3 bump mapping
//   reference 1 ch  exact ray-cast lit map for the light (lx, ly, sqrt(1-lx^2-ly^2)): 0 or 255
//   soft      1 ch  visible fraction of a disc light of angular diameter `diameter` (codes round half up)
//   ellipse   1 ch  the float64 ellipse test d >= 0 (255) or < 0 (0): the ellipse's own error, no hardware
// The fit is memoised in-process by the canonical description of the field and
// the options, and kept on disk by bumpshadow's cache (`cache=DIR`, default
// out/cache relative to the working directory; `cache=none` disables it).
// `field` is a generator name or an expression giving its index 0..4 in
// bump, bumps, ridges, craters, fractal, so a trace parameter can select it.

const std::vector<std::string>& field_names() {
  static const std::vector<std::string> n = {"bump", "bumps", "ridges", "craters", "fractal"};
  return n;
}

const bumpshadow::GeneratorInfo& field_info(const std::string& name) {
  for (const auto& g : bumpshadow::generators())
    if (g.name == name) return g;
  throw std::runtime_error(std::string("no height-field generator `") + name + "`");
}

// Reads the keys of height-field generator `name` from a and builds the field
// (heights times `scale`). `desc` receives the canonical description.
bumpshadow::HeightField read_field(GeneratorArgs& a, const std::string& name, std::string& desc) {
  bumpshadow::GeneratorParams p;
  for (const auto& k : field_info(name).params) {
    if (!a.has(k.key)) continue;
    if (k.key == "border")
      p[k.key] = a.word("border", {"wrap", "clamp"});
    else
      p[k.key] = format_number(a.number(k.key, 0));
  }
  const double scale = a.number("scale", 1);
  if (!(scale > 0) || !std::isfinite(scale))
    throw TraceError(a.where("scale"), std::string("`scale` must be a positive number, got ") + format_number(scale), a.line());
  desc = bumpshadow::describe_generator(name, p) + " scale=" + format_number(scale);
  bumpshadow::HeightField hf = bumpshadow::generate(name, p);
  if (static_cast<long long>(hf.width()) * hf.height() > a.max_pixels())
    throw TraceError(a.where("w"), std::string("field size ") + std::to_string(hf.width()) + "x" + std::to_string(hf.height()) +
                                       " exceeds the limit of " + std::to_string(a.max_pixels()) + " pixels", a.line());
  return scale == 1 ? hf : hf.scaled(scale);
}

Image byte_image(const bumpshadow::ByteMap& m) {
  Image im = Image::make(m.width, m.height, m.channels, SampleType::U8);
  im.u8 = m.v;
  return im;
}

Image byte_image(int w, int h, const std::vector<std::uint8_t>& v) {
  Image im = Image::make(w, h, 1, SampleType::U8);
  im.u8 = v;
  return im;
}

std::mutex& memo_mutex() {
  static std::mutex m;
  return m;
}

// The ellipse map of a field, memoised by (field description, options text).
std::shared_ptr<const bumpshadow::EllipseMap> ellipse_map_for(const bumpshadow::HeightField& hf, const std::string& desc,
                                                             const bumpshadow::ShadowMapOptions& o,
                                                             const std::string& cache) {
  static std::map<std::string, std::shared_ptr<const bumpshadow::EllipseMap>> memo;
  const std::string key = desc + " | " + bumpshadow::describe_options(o);
  {
    std::lock_guard<std::mutex> lock(memo_mutex());
    auto it = memo.find(key);
    if (it != memo.end()) return it->second;
  }
  auto m = std::make_shared<const bumpshadow::EllipseMap>(
      cache == "none" ? bumpshadow::compute_ellipse_map(hf, o) : bumpshadow::cached_ellipse_map(hf, o, cache));
  std::lock_guard<std::mutex> lock(memo_mutex());
  return memo.emplace(key, std::move(m)).first->second;
}

std::shared_ptr<const bumpshadow::EncodedMaps> encoded_maps_for(const bumpshadow::EllipseMap& em, const std::string& key) {
  static std::map<std::string, std::shared_ptr<const bumpshadow::EncodedMaps>> memo;
  {
    std::lock_guard<std::mutex> lock(memo_mutex());
    auto it = memo.find(key);
    if (it != memo.end()) return it->second;
  }
  auto e = std::make_shared<const bumpshadow::EncodedMaps>(bumpshadow::encode_maps(em));
  std::lock_guard<std::mutex> lock(memo_mutex());
  return memo.emplace(key, std::move(e)).first->second;
}

bumpshadow::Vec3 light_from(GeneratorArgs& a) {
  const double lx = a.number("lx", 0.3), ly = a.number("ly", 0.4);
  const double r2 = lx * lx + ly * ly;
  if (!(r2 < 1))
    throw TraceError(a.where(a.has("lx") ? "lx" : "ly"),
                     std::string("the light (lx, ly) = (") + format_number(lx) + ", " + format_number(ly) +
                         ") must lie inside the unit disc (lz = sqrt(1 - lx^2 - ly^2) > 0)", a.line());
  return {lx, ly, std::sqrt(1 - r2)};
}

// The `field` key (a generator name, or an index expression so a parameter can
// choose) and that field's own keys; desc receives its description.
bumpshadow::HeightField field_argument(GeneratorArgs& a, std::string& desc) {
  std::string field;
  const std::string ft = a.text("field", "bumps");
  for (const auto& n : field_names())
    if (n == ft) field = n;
  if (field.empty()) field = field_names()[static_cast<std::size_t>(a.integer("field", 1, 0, 4))];
  return read_field(a, field, desc);
}

Image shadowmap(GeneratorArgs& a) {
  std::string desc;
  bumpshadow::HeightField hf = field_argument(a, desc);
  const std::string map =
      a.word("map", {"t1r", "t2r", "t3r", "t1n", "t2n", "normal", "reference", "soft", "ellipse"});
  if (map == "normal") {
    a.finish();
    return byte_image(bumpshadow::quantise(bumpshadow::normal_map(hf)));
  }
  if (map == "reference" || map == "soft") {
    const bumpshadow::Vec3 L = light_from(a);
    const double diameter = map == "soft" ? a.number("diameter", 0.2) : 0;
    const int samples = map == "soft" ? static_cast<int>(a.integer("samples", 64, 1, 4096)) : 0;
    if (map == "soft" && !(diameter > 0 && diameter < 3.14159))
      throw TraceError(a.where("diameter"), std::string("`diameter` must be in (0, pi) radians, got ") + format_number(diameter), a.line());
    a.finish();
    if (map == "reference") {
      std::vector<std::uint8_t> lit = bumpshadow::reference_lit_map(hf, L);
      for (auto& v : lit) v = v ? 255 : 0;
      return byte_image(hf.width(), hf.height(), lit);
    }
    const std::vector<double> f = bumpshadow::reference_soft_map(hf, L, diameter, samples);
    std::vector<std::uint8_t> codes(f.size());
    for (std::size_t i = 0; i < f.size(); ++i) codes[i] = static_cast<std::uint8_t>(unorm_from_double(f[i], 8));
    return byte_image(hf.width(), hf.height(), codes);
  }
  bumpshadow::ShadowMapOptions o;
  o.rays = bumpshadow::rays_for_count(static_cast<int>(a.integer("rays", 256, 4, 1 << 20)));
  o.rays.seed = static_cast<std::uint64_t>(a.integer("rayseed", 1, 0, 1ll << 53));
  const std::string cache = a.text("cache", "out/cache");
  bumpshadow::Vec3 L;
  if (map == "ellipse") L = light_from(a);
  a.finish();
  auto em = ellipse_map_for(hf, desc, o, cache);
  if (map == "ellipse") {
    const std::vector<double> d = bumpshadow::ellipse_test_map(*em, L);
    std::vector<std::uint8_t> lit(d.size());
    for (std::size_t i = 0; i < d.size(); ++i) lit[i] = d[i] >= 0 ? 255 : 0;
    return byte_image(em->width, em->height, lit);
  }
  auto enc = encoded_maps_for(*em, desc + " | " + bumpshadow::describe_options(o));
  if (map == "t1r") return byte_image(enc->t1r8);
  if (map == "t2r") return byte_image(enc->t2r8);
  if (map == "t3r") return byte_image(enc->t3r8);
  if (map == "t1n") return byte_image(enc->t1n8);
  return byte_image(enc->t2n8);
}

// ---- [issue 9] Max's horizon map as the 8-bit textures hardware of 2000 would use ----
//
// `generate H0 horizon field=bumps w=64 azimuths=16 index=3` gives one channel per
// texel: the horizon elevation beta (radians, bumpshadow::compute_horizon_map)
// toward azimuth theta_index = 2 pi index / azimuths, encoded linearly in angle as
// code = round(beta / (pi/2) * 255) (unorm_from_double, round half up). Linear in
// angle because Max interpolates the angle linearly between azimuths, which a
// texture environment INTERPOLATE (or bilinear filtering between texels) then does
// exactly, and because one code is the same 0.35 degrees at every elevation, so
// grazing lights (5 degrees) are resolved as well as steep ones. The horizon map is
// memoised in-process and cached on disk like the ellipse fit (`cache`).
std::mutex& horizon_memo_mutex() {
  static std::mutex m;
  return m;
}

Image horizon(GeneratorArgs& a) {
  std::string desc;
  bumpshadow::HeightField hf = field_argument(a, desc);
  const int n = static_cast<int>(a.integer("azimuths", 16, 1, 1024));
  const int index = static_cast<int>(a.integer("index", 0, 0, n - 1));
  const std::string cache = a.text("cache", "out/cache");
  a.finish();
  static std::map<std::string, std::shared_ptr<const bumpshadow::HorizonMap>> memo;
  const std::string key = desc + " | azimuths=" + std::to_string(n);
  std::shared_ptr<const bumpshadow::HorizonMap> hm;
  {
    std::lock_guard<std::mutex> lock(horizon_memo_mutex());
    auto it = memo.find(key);
    if (it != memo.end()) hm = it->second;
  }
  if (!hm) {
    auto m = std::make_shared<const bumpshadow::HorizonMap>(
        cache == "none" ? bumpshadow::compute_horizon_map(hf, n) : bumpshadow::cached_horizon_map(hf, n, {}, cache));
    std::lock_guard<std::mutex> lock(horizon_memo_mutex());
    hm = memo.emplace(key, std::move(m)).first->second;
  }
  std::vector<std::uint8_t> codes(static_cast<std::size_t>(hm->width) * hm->height);
  const double half_pi = 1.5707963267948966;
  for (int y = 0; y < hm->height; ++y)
    for (int x = 0; x < hm->width; ++x)
      codes[static_cast<std::size_t>(y) * hm->width + x] =
          static_cast<std::uint8_t>(unorm_from_double(std::clamp(hm->at(x, y, index) / half_pi, 0.0, 1.0), 8));
  return byte_image(hm->width, hm->height, codes);
}

GeneratorRegistry build() {
  GeneratorRegistry r;
  r.add({"hemisphere_bump", "width=64 height=64 radius=16 border=clamp|wrap",
         "one hemispherical bump centred in the field; heights in texel units (bumpshadow/heightfield.h)",
         [](GeneratorArgs& a) {
           const auto [w, h] = a.size("width", "height", 64);
           const double radius = a.number("radius", 16);
           const bumpshadow::Border border =
               a.word("border", {"clamp", "wrap"}) == "wrap" ? bumpshadow::Border::Wrap : bumpshadow::Border::Clamp;
           a.finish();
           return heightfield_image(bumpshadow::hemisphere_bump(w, h, radius, border));
         }});
  // ==== [issue 7] bumpshadow generators ====
  for (const auto& g : bumpshadow::generators()) {
    std::string keys;
    for (const auto& k : g.params) keys += (keys.empty() ? "" : " ") + k.key + (k.default_value.empty() ? "" : "=" + k.default_value);
    const std::string name = g.name;
    r.add({name, keys + " scale=1", g.summary + "; 1-channel float heights in texel units (docs/bumpshadow.md §2)",
           [name](GeneratorArgs& a) {
             std::string desc;
             const bumpshadow::HeightField hf = read_field(a, name, desc);
             a.finish();
             return heightfield_image(hf);
           }});
  }
  r.add({"shadowmap",
         "field=bumps|INDEX (the field's keys) scale=1 rays=256 rayseed=1 cache=out/cache|none "
         "map=t1r|t2r|t3r|t1n|t2n|normal|reference|soft|ellipse lx=0.3 ly=0.4 diameter=0.2 samples=64",
         "the paper's 8-bit maps of a generated field (T1^r, T2^r, T3^r, T1^n, T2^n as bumpshadow::encode_maps), "
         "its normal map, and the exact, soft and float64-ellipse lit maps for a light",
         shadowmap});
  r.add({"horizon", "field=bumps|INDEX (the field's keys) scale=1 azimuths=16 index=0 cache=out/cache|none",
         "Max's horizon map of a generated field toward azimuth 2 pi index / azimuths: 8-bit, "
         "code = round(elevation / (pi/2) * 255) (docs/bumpshadow.md §7.1)",
         horizon});

  return r;
}

}  // namespace

const GeneratorRegistry& generators() {
  static const GeneratorRegistry r = build();
  return r;
}

}  // namespace ffsim::trace
