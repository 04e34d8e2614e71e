#include "sim/trace/generators.h"

#include <cmath>
#include <limits>
#include <stdexcept>

#include "bumpshadow/generators.h"
#include "bumpshadow/heightfield.h"

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

  return r;
}

}  // namespace

const GeneratorRegistry& generators() {
  static const GeneratorRegistry r = build();
  return r;
}

}  // namespace ffsim::trace
