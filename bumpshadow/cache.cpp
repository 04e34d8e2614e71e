#include "bumpshadow/cache.h"

#include <bit>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace ffsim::bumpshadow {

namespace {

constexpr char kMagic[8] = {'F', 'F', 'S', 'I', 'M', 'B', 'S', '1'};

std::string hex(std::uint64_t v) {
  char buf[17];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(v));
  return buf;
}

class Writer {
 public:
  void u64(std::uint64_t v) {
    for (int i = 0; i < 8; ++i) s_.push_back(static_cast<char>(v >> (8 * i)));
  }
  void f64(double d) { u64(std::bit_cast<std::uint64_t>(d)); }
  void u8(std::uint8_t b) { s_.push_back(static_cast<char>(b)); }
  void raw(const char* p, std::size_t n) { s_.append(p, n); }
  const std::string& str() const { return s_; }

 private:
  std::string s_;
};

class Reader {
 public:
  explicit Reader(std::string s) : s_(std::move(s)) {}
  bool ok() const { return ok_; }
  std::uint64_t u64() {
    if (pos_ + 8 > s_.size()) return fail();
    std::uint64_t v = 0;
    for (int i = 0; i < 8; ++i) v |= static_cast<std::uint64_t>(static_cast<unsigned char>(s_[pos_ + i])) << (8 * i);
    pos_ += 8;
    return v;
  }
  double f64() { return std::bit_cast<double>(u64()); }
  std::uint8_t u8() {
    if (pos_ + 1 > s_.size()) return static_cast<std::uint8_t>(fail());
    return static_cast<std::uint8_t>(s_[pos_++]);
  }
  bool magic() {
    if (pos_ + 8 > s_.size()) return fail() != 0;
    for (int i = 0; i < 8; ++i)
      if (s_[pos_ + i] != kMagic[i]) return fail() != 0;
    pos_ += 8;
    return true;
  }
  bool at_end() const { return pos_ == s_.size(); }

 private:
  std::uint64_t fail() {
    ok_ = false;
    pos_ = s_.size();
    return 0;
  }
  std::string s_;
  std::size_t pos_ = 0;
  bool ok_ = true;
};

bool read_file(const std::string& path, std::string& out) {
  std::ifstream f(path, std::ios::binary);
  if (!f) return false;
  std::ostringstream ss;
  ss << f.rdbuf();
  out = ss.str();
  return true;
}

void write_file(const std::string& dir, const std::string& name, const std::string& data) {
  std::filesystem::create_directories(dir);
  const std::string path = dir + "/" + name, tmp = path + ".tmp";
  {
    std::ofstream f(tmp, std::ios::binary | std::ios::trunc);
    if (!f) throw HeightFieldError("cannot write cache file " + tmp);
    f.write(data.data(), static_cast<std::streamsize>(data.size()));
    if (!f) throw HeightFieldError("cannot write cache file " + tmp);
  }
  std::filesystem::rename(tmp, path);
}

}  // namespace

std::uint64_t ellipse_map_key(const HeightField& hf, const ShadowMapOptions& o) {
  Fnv64 f;
  f.str("ffsim-bumpshadow-ellipse-1");
  f.u64(hf.hash());
  f.str(describe_options(o));
  return f.state;
}

std::uint64_t horizon_map_key(const HeightField& hf, int azimuths, const MarchOptions& m) {
  Fnv64 f;
  f.str("ffsim-bumpshadow-horizon-1");
  f.u64(hf.hash());
  f.u64(static_cast<std::uint64_t>(azimuths));
  f.f64(m.step);
  f.f64(m.max_distance);
  return f.state;
}

EllipseMap cached_ellipse_map(const HeightField& hf, const ShadowMapOptions& o, const std::string& dir, bool* hit) {
  const std::uint64_t key = ellipse_map_key(hf, o);
  const std::string name = "ellipse-" + hex(key) + ".bin";
  std::string data;
  if (read_file(dir + "/" + name, data)) {
    Reader r(std::move(data));
    EllipseMap m;
    if (r.magic() && r.u8() == 'E' && r.u64() == key) {
      m.width = static_cast<int>(r.u64());
      m.height = static_cast<int>(r.u64());
      m.rays_per_texel = static_cast<int>(r.u64());
      const std::size_t n = static_cast<std::size_t>(m.width) * m.height;
      if (r.ok() && n == static_cast<std::size_t>(hf.width()) * hf.height()) {
        m.ellipse.resize(n);
        m.kind.resize(n);
        m.agree.resize(n);
        for (std::size_t t = 0; t < n && r.ok(); ++t) {
          Ellipse& e = m.ellipse[t];
          e.cx = r.f64(), e.cy = r.f64(), e.ax = r.f64(), e.ay = r.f64(), e.rx = r.f64(), e.ry = r.f64();
          const std::uint8_t k = r.u8();
          if (k >= kTexelKinds) break;
          m.kind[t] = static_cast<TexelKind>(k);
          m.agree[t] = static_cast<std::uint32_t>(r.u64());
        }
        if (r.ok() && r.at_end()) {
          for (TexelKind k : m.kind) ++m.kind_count[static_cast<int>(k)];
          if (hit) *hit = true;
          return m;
        }
      }
    }
  }
  EllipseMap m = compute_ellipse_map(hf, o);
  Writer w;
  w.raw(kMagic, 8);
  w.u8('E');
  w.u64(key);
  w.u64(static_cast<std::uint64_t>(m.width));
  w.u64(static_cast<std::uint64_t>(m.height));
  w.u64(static_cast<std::uint64_t>(m.rays_per_texel));
  for (std::size_t t = 0; t < m.ellipse.size(); ++t) {
    const Ellipse& e = m.ellipse[t];
    for (double v : {e.cx, e.cy, e.ax, e.ay, e.rx, e.ry}) w.f64(v);
    w.u8(static_cast<std::uint8_t>(m.kind[t]));
    w.u64(m.agree[t]);
  }
  write_file(dir, name, w.str());
  if (hit) *hit = false;
  return m;
}

HorizonMap cached_horizon_map(const HeightField& hf, int azimuths, const MarchOptions& m, const std::string& dir,
                              int threads, const Progress& progress, bool* hit) {
  const std::uint64_t key = horizon_map_key(hf, azimuths, m);
  const std::string name = "horizon-" + hex(key) + ".bin";
  std::string data;
  if (read_file(dir + "/" + name, data)) {
    Reader r(std::move(data));
    HorizonMap h;
    if (r.magic() && r.u8() == 'H' && r.u64() == key) {
      h.width = static_cast<int>(r.u64());
      h.height = static_cast<int>(r.u64());
      h.azimuths = static_cast<int>(r.u64());
      const std::size_t n = static_cast<std::size_t>(hf.width()) * hf.height() * azimuths;
      if (r.ok() && h.width == hf.width() && h.height == hf.height() && h.azimuths == azimuths) {
        h.elevation.resize(n);
        for (std::size_t t = 0; t < n && r.ok(); ++t) h.elevation[t] = r.f64();
        if (r.ok() && r.at_end()) {
          if (hit) *hit = true;
          return h;
        }
      }
    }
  }
  HorizonMap h = compute_horizon_map(hf, azimuths, m, threads, progress);
  Writer w;
  w.raw(kMagic, 8);
  w.u8('H');
  w.u64(key);
  w.u64(static_cast<std::uint64_t>(h.width));
  w.u64(static_cast<std::uint64_t>(h.height));
  w.u64(static_cast<std::uint64_t>(h.azimuths));
  for (double v : h.elevation) w.f64(v);
  write_file(dir, name, w.str());
  if (hit) *hit = false;
  return h;
}

}  // namespace ffsim::bumpshadow
