#include "pipeline/number/unorm.h"

#include <bit>
#include <cassert>
#include <cmath>

namespace ffsim {

__extension__ typedef unsigned __int128 u128;  // GCC/Clang on every 64-bit target

std::uint32_t unorm_from_double(double x, int bits) {
  assert(bits >= kMinUnormBits && bits <= kMaxUnormBits);
  const std::uint32_t m = unorm_max(bits);
  if (std::isnan(x) || x <= 0.0) return 0;  // NaN -> 0 by choice (docs/numerics.md §1.3)
  if (x >= 1.0) return m;                   // clamp to [0,1] (§2.13.9)
  // x = mant * 2^-s exactly, mant < 2^53. Then x*m = mant*m / 2^s is an exact
  // rational and floor(x*m + 1/2) = (mant*m + 2^(s-1)) >> s in 128-bit integers.
  // mant and s straight from the binary64 fields (no frexp/ldexp calls): a normal
  // x is (2^52 + fraction)·2^(E − 1075) for its biased exponent E, so s = 1075 − E
  // (>= 54 because x < 1 => E <= 1022); a subnormal (E = 0) has s >= 1074.
  const auto bits64 = std::bit_cast<std::uint64_t>(x);
  const int E = static_cast<int>(bits64 >> 52);  // the sign bit is 0 here (x > 0)
  const std::uint64_t mant = (bits64 & ((std::uint64_t{1} << 52) - 1)) | (E ? std::uint64_t{1} << 52 : 0);
  const int s = E ? 1075 - E : 1074;
  if (s >= 120) return 0;  // x*m < 2^(53+24-120): far below 1/2
  const u128 p = static_cast<u128>(mant) * m + (static_cast<u128>(1) << (s - 1));
  return static_cast<std::uint32_t>(p >> s);
}

std::uint32_t unorm_convert(std::uint32_t k, int from_bits, int to_bits) {
  assert(from_bits >= kMinUnormBits && from_bits <= kMaxUnormBits);
  assert(to_bits >= kMinUnormBits && to_bits <= kMaxUnormBits);
  const std::uint32_t mf = unorm_max(from_bits);
  if (k > mf) k = mf;
  if (from_bits == to_bits) return k;
  return static_cast<std::uint32_t>(div_round_half_up(std::uint64_t{k} * unorm_max(to_bits), mf));
}

}  // namespace ffsim
