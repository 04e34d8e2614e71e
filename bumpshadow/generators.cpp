#include "bumpshadow/generators.h"

#include "bumpshadow/detmath.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <numbers>
#include <sstream>

#include "bumpshadow/rng.h"

namespace ffsim::bumpshadow {

HeightField hemisphere_bump(int width, int height, double radius, double cx, double cy, Border border) {
  if (!(radius > 0) || !std::isfinite(radius))
    throw HeightFieldError("bump radius " + std::to_string(radius) + " must be finite and > 0");
  if (width < 1 || height < 1)  // the HeightField constructor words the error
    return HeightField(width, height, {}, border);
  std::vector<double> z(static_cast<std::size_t>(width) * height, 0.0);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const double dx = x - cx, dy = y - cy, r2 = radius * radius - dx * dx - dy * dy;
      z[static_cast<std::size_t>(y) * width + x] = r2 > 0 ? std::sqrt(r2) : 0.0;
    }
  return HeightField(width, height, std::move(z), border);
}

HeightField hemisphere_bump(int width, int height, double radius, Border border) {
  return hemisphere_bump(width, height, radius, std::floor(0.5 * width), std::floor(0.5 * height), border);
}

namespace {

// Reads typed values from the params, with defaults and validation.
class Args {
 public:
  Args(const GeneratorInfo& info, const GeneratorParams& p) : info_(info), p_(p) {
    for (const auto& [k, v] : p_) {
      bool known = false;
      for (const auto& pi : info_.params) known = known || pi.key == k;
      if (!known) {
        std::string keys;
        for (const auto& pi : info_.params) keys += (keys.empty() ? "" : ", ") + pi.key;
        throw HeightFieldError("generator `" + info_.name + "`: unknown parameter `" + k + "` (accepted: " + keys + ")");
      }
    }
  }
  std::string raw(const std::string& key) const {
    auto it = p_.find(key);
    if (it != p_.end()) return it->second;
    for (const auto& pi : info_.params)
      if (pi.key == key) return pi.default_value;
    return "";
  }
  double num(const std::string& key, double lo, double hi) const {
    const std::string s = raw(key);
    std::size_t used = 0;
    double v = 0;
    try {
      v = std::stod(s, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (s.empty() || used != s.size() || !std::isfinite(v))
      throw HeightFieldError("generator `" + info_.name + "`: " + key + "=`" + s + "` is not a finite number");
    if (v < lo || v > hi) {
      std::ostringstream o;
      o << "generator `" << info_.name << "`: " << key << "=" << s << " is out of range [" << lo << ", " << hi << "]";
      throw HeightFieldError(o.str());
    }
    return v;
  }
  int integer(const std::string& key, int lo, int hi) const {
    const double v = num(key, lo, hi);
    if (v != std::floor(v))
      throw HeightFieldError("generator `" + info_.name + "`: " + key + "=" + raw(key) + " must be an integer");
    return static_cast<int>(v);
  }
  std::uint64_t seed() const {
    const std::string s = raw("seed");
    if (s.empty() || s.size() > 19 || s.find_first_not_of("0123456789") != std::string::npos)
      throw HeightFieldError("generator `" + info_.name + "`: seed=`" + s + "` must be a decimal integer < 10^19");
    return std::stoull(s);
  }
  Border border() const {
    const std::string s = raw("border");
    if (s == "wrap") return Border::Wrap;
    if (s == "clamp") return Border::Clamp;
    throw HeightFieldError("generator `" + info_.name + "`: border=`" + s + "` must be wrap or clamp");
  }
  int w() const { return integer("w", 2, kMaxHeightFieldSide); }
  int h() const { return raw("h").empty() ? w() : integer("h", 2, kMaxHeightFieldSide); }

 private:
  const GeneratorInfo& info_;
  const GeneratorParams& p_;
};

std::vector<GeneratorParamInfo> common(const char* border) {
  return {{"w", "64", "width in texels"},
          {"h", "", "height in texels (default: w)"},
          {"border", border, "wrap (tiles) or clamp (edge plateaus)"},
          {"seed", "1", "seed of the random choices (decimal)"}};
}

std::vector<GeneratorParamInfo> plus(std::vector<GeneratorParamInfo> a, std::vector<GeneratorParamInfo> b) {
  a.insert(a.end(), b.begin(), b.end());
  return a;
}

// Periodic distance component for wrap fields, plain difference for clamp.
double delta(double a, double b, int n, Border border) {
  double d = a - b;
  if (border == Border::Wrap) d -= n * std::round(d / n);
  return d;
}

void check_size(int w, int h) {
  if (static_cast<long long>(w) * h > kMaxHeightFieldTexels)
    throw HeightFieldError("height field size " + std::to_string(w) + "x" + std::to_string(h) +
                           " exceeds 2^26 texels");
}

HeightField gen_bump(const Args& a) {
  const int w = a.w(), h = a.h();
  check_size(w, h);
  const double r = a.num("r", 0.5, 1e4);
  const double cx = a.raw("cx").empty() ? std::floor(0.5 * w) : a.num("cx", -1e6, 1e6);
  const double cy = a.raw("cy").empty() ? std::floor(0.5 * h) : a.num("cy", -1e6, 1e6);
  return hemisphere_bump(w, h, r, cx, cy, a.border());
}

HeightField gen_bumps(const Args& a) {
  const int w = a.w(), h = a.h();
  check_size(w, h);
  const double sp = a.num("spacing", 2, 1e4), r = a.num("r", 0.5, 1e4), jit = a.num("jitter", 0, 1);
  const std::uint64_t seed = a.seed();
  const Border b = a.border();
  const int nx = std::max(1, static_cast<int>(std::floor(w / sp))), ny = std::max(1, static_cast<int>(std::floor(h / sp)));
  std::vector<double> z(static_cast<std::size_t>(w) * h, 0.0);
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const double ox = jit * (u01(hash_u64(seed, 1, i, j)) - 0.5) * sp;
      const double oy = jit * (u01(hash_u64(seed, 2, i, j)) - 0.5) * sp;
      const double cx = (i + 0.5) * w / nx + ox, cy = (j + 0.5) * h / ny + oy;
      for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
          const double dx = delta(x, cx, w, b), dy = delta(y, cy, h, b), r2 = r * r - dx * dx - dy * dy;
          double& v = z[static_cast<std::size_t>(y) * w + x];
          if (r2 > 0) v = std::max(v, std::sqrt(r2));
        }
    }
  return HeightField(w, h, std::move(z), b);
}

HeightField gen_ridges(const Args& a) {
  const int w = a.w(), h = a.h();
  check_size(w, h);
  const double period = a.num("period", 2, 1e4), width = a.num("width", 0.5, 1e4), height = a.num("height", 0, 1e4);
  const double ang = a.num("angle", -360, 360) * std::numbers::pi / 180.0;
  const double nx = det::cos(ang), ny = det::sin(ang);  // across-ridge direction
  std::vector<double> z(static_cast<std::size_t>(w) * h, 0.0);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const double s = x * nx + y * ny;
      const double d = std::abs(s - period * std::round(s / period));  // distance to the nearest ridge line
      z[static_cast<std::size_t>(y) * w + x] = height * std::max(0.0, 1.0 - d / (0.5 * width));
    }
  return HeightField(w, h, std::move(z), a.border());
}

// Max's moon: craters of random centre and radius; a parabolic bowl below the
// ground with a raised rim that falls off outside the radius. Summed.
HeightField gen_craters(const Args& a) {
  const int w = a.w(), h = a.h();
  check_size(w, h);
  const int n = a.integer("count", 0, 100000);
  const double rmin = a.num("rmin", 0.5, 1e4), rmax = a.num("rmax", 0.5, 1e4), depth = a.num("depth", 0, 1e4);
  if (rmax < rmin) throw HeightFieldError("generator `craters`: rmax must be >= rmin");
  const Border b = a.border();
  SplitMix64 rng(a.seed());
  std::vector<double> z(static_cast<std::size_t>(w) * h, 0.0);
  for (int k = 0; k < n; ++k) {
    const double cx = rng.uniform(0, w), cy = rng.uniform(0, h), R = rng.uniform(rmin, rmax);
    const double d = depth * R / rmax, rim = 0.35 * d;
    const int ext = static_cast<int>(std::ceil(1.6 * R)) + 1;
    for (int yy = static_cast<int>(std::floor(cy)) - ext; yy <= static_cast<int>(std::floor(cy)) + ext; ++yy)
      for (int xx = static_cast<int>(std::floor(cx)) - ext; xx <= static_cast<int>(std::floor(cx)) + ext; ++xx) {
        int x = xx, y = yy;
        if (b == Border::Wrap) {
          x = ((x % w) + w) % w;
          y = ((y % h) + h) % h;
        } else if (x < 0 || y < 0 || x >= w || y >= h) {
          continue;
        }
        const double rr = std::sqrt((xx - cx) * (xx - cx) + (yy - cy) * (yy - cy)) / R;
        double v = 0;
        if (rr < 1) v = (d + rim) * rr * rr - d;                  // bowl: -d at the centre, +rim at the edge
        else if (rr < 1.6) v = rim * ((1.6 - rr) / 0.6) * ((1.6 - rr) / 0.6);  // rim falling to 0 at 1.6 R
        z[static_cast<std::size_t>(y) * w + x] += v;
      }
  }
  return HeightField(w, h, std::move(z), b);
}

// fBm of value noise on periodic lattices (octave o has base*2^o cells across
// the field, so the field tiles for any size); smoothstep-faded bilinear lattice
// interpolation; amplitude halves (gain) per octave; normalised so that the sum
// of amplitudes equals `height`.
HeightField gen_fractal(const Args& a) {
  const int w = a.w(), h = a.h();
  check_size(w, h);
  const int octaves = a.integer("octaves", 1, 12), base = a.integer("base", 1, 4096);
  const double gain = a.num("gain", 0, 1), height = a.num("height", 0, 1e4);
  const std::uint64_t seed = a.seed();
  std::vector<double> z(static_cast<std::size_t>(w) * h, 0.0);
  double amp = 1, total = 0;
  for (int o = 0; o < octaves; ++o) {
    const long long f = static_cast<long long>(base) << o;
    auto lattice = [&](long long i, long long j) {
      i = ((i % f) + f) % f;
      j = ((j % f) + f) % f;
      return u01(hash_u64(seed, static_cast<std::uint64_t>(o), static_cast<std::uint64_t>(i), static_cast<std::uint64_t>(j)));
    };
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        const double gx = static_cast<double>(x) * f / w, gy = static_cast<double>(y) * f / h;
        const double fx = std::floor(gx), fy = std::floor(gy);
        double tx = gx - fx, ty = gy - fy;
        tx = tx * tx * (3 - 2 * tx);
        ty = ty * ty * (3 - 2 * ty);
        const long long i = static_cast<long long>(fx), j = static_cast<long long>(fy);
        const double v0 = lattice(i, j) + (lattice(i + 1, j) - lattice(i, j)) * tx;
        const double v1 = lattice(i, j + 1) + (lattice(i + 1, j + 1) - lattice(i, j + 1)) * tx;
        z[static_cast<std::size_t>(y) * w + x] += amp * (v0 + (v1 - v0) * ty);
      }
    total += amp;
    amp *= gain;
  }
  for (double& v : z) v *= height / total;
  return HeightField(w, h, std::move(z), a.border());
}

struct Entry {
  GeneratorInfo info;
  std::function<HeightField(const Args&)> make;
};

const std::vector<Entry>& registry() {
  static const std::vector<Entry> all = {
      {{"bump", "one hemispherical bump of radius r centred on texel (cx, cy) over flat ground",
        plus(common("clamp"), {{"r", "16", "radius in texels (also the peak height)"},
                               {"cx", "", "centre column (default floor(w/2))"},
                               {"cy", "", "centre row (default floor(h/2))"}})},
       gen_bump},
      {{"bumps", "a regular grid of hemispherical bumps (optionally jittered)",
        plus(common("wrap"), {{"spacing", "16", "grid pitch in texels"},
                              {"r", "6", "bump radius in texels"},
                              {"jitter", "0", "random centre offset, fraction of the pitch (0..1)"}})},
       gen_bumps},
      {{"ridges", "long parallel ridges with a triangular profile (Max's figures)",
        plus(common("wrap"), {{"period", "16", "ridge spacing in texels"},
                              {"width", "6", "ridge base width in texels"},
                              {"height", "4", "ridge height in texels"},
                              {"angle", "0", "direction across the ridges, degrees from +x (0 and 90 tile)"}})},
       gen_ridges},
      {{"craters", "random craters with raised rims (Max's moon)",
        plus(common("wrap"), {{"count", "24", "number of craters"},
                              {"rmin", "3", "smallest radius in texels"},
                              {"rmax", "10", "largest radius in texels"},
                              {"depth", "4", "bowl depth of the largest crater in texels"}})},
       gen_craters},
      {{"fractal", "fractal terrain: fBm of periodic value noise",
        plus(common("wrap"), {{"octaves", "5", "number of octaves"},
                              {"base", "4", "lattice cells across the field at octave 0"},
                              {"gain", "0.5", "amplitude factor per octave"},
                              {"height", "8", "total relief in texels (sum of octave amplitudes)"}})},
       gen_fractal},
  };
  return all;
}

const Entry& find(const std::string& name) {
  for (const auto& e : registry())
    if (e.info.name == name) return e;
  std::string names;
  for (const auto& e : registry()) names += (names.empty() ? "" : ", ") + e.info.name;
  throw HeightFieldError("unknown height field generator `" + name + "` (known: " + names + ")");
}

}  // namespace

const std::vector<GeneratorInfo>& generators() {
  static const std::vector<GeneratorInfo> infos = [] {
    std::vector<GeneratorInfo> v;
    for (const auto& e : registry()) v.push_back(e.info);
    return v;
  }();
  return infos;
}

HeightField generate(const std::string& name, const GeneratorParams& params) {
  const Entry& e = find(name);
  return e.make(Args(e.info, params));
}

std::string describe_generator(const std::string& name, const GeneratorParams& params) {
  const Entry& e = find(name);
  Args a(e.info, params);
  std::map<std::string, std::string> all;
  for (const auto& pi : e.info.params) all[pi.key] = a.raw(pi.key);
  std::string s = name;
  for (const auto& [k, v] : all)
    if (!v.empty()) s += " " + k + "=" + v;
  return s;
}

GeneratorParams parse_generator_params(const std::vector<std::string>& kv) {
  GeneratorParams p;
  for (const auto& s : kv) {
    const auto eq = s.find('=');
    if (eq == std::string::npos || eq == 0)
      throw HeightFieldError("generator parameter `" + s + "` is not of the form key=value");
    p[s.substr(0, eq)] = s.substr(eq + 1);
  }
  return p;
}

}  // namespace ffsim::bumpshadow
