// Deterministic pseudo-random numbers (no std:: distributions: their output is
// implementation-defined). splitmix64 (Steele, Lea, Flood 2014) and a uniform
// mapping of the top 53 bits to [0, 1): the same bits on every platform.
#pragma once
#include <cstdint>

namespace ffsim::bumpshadow {

constexpr std::uint64_t splitmix64_mix(std::uint64_t z) {
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
  return z ^ (z >> 31);
}

// A counter-based hash of up to four integers: stateless, so any texel or ray can
// be generated independently (thread-count independent by construction).
constexpr std::uint64_t hash_u64(std::uint64_t a, std::uint64_t b = 0, std::uint64_t c = 0, std::uint64_t d = 0) {
  std::uint64_t h = splitmix64_mix(a + 0x9e3779b97f4a7c15ull);
  h = splitmix64_mix(h ^ (b + 0x9e3779b97f4a7c15ull));
  h = splitmix64_mix(h ^ (c + 0x9e3779b97f4a7c15ull));
  return splitmix64_mix(h ^ (d + 0x9e3779b97f4a7c15ull));
}

// Top 53 bits / 2^53: uniform on [0, 1), exact in binary64.
constexpr double u01(std::uint64_t bits) { return static_cast<double>(bits >> 11) * 0x1.0p-53; }

class SplitMix64 {
 public:
  explicit SplitMix64(std::uint64_t seed) : s_(seed) {}
  std::uint64_t next() { return splitmix64_mix(s_ += 0x9e3779b97f4a7c15ull); }
  double uniform() { return u01(next()); }                                   // [0, 1)
  double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }  // [lo, hi)

 private:
  std::uint64_t s_;
};

}  // namespace ffsim::bumpshadow
