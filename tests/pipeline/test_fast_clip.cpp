// clip_polygon's shortcut (wholly inside: unchanged; wholly outside one plane:
// nothing) against the six Sutherland-Hodgman passes alone, over seeded random
// polygons: every vertex attribute must be bit-identical.
#include <doctest/doctest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <random>

#include "pipeline/geometry/clip.h"

using namespace ffsim;

namespace {

bool same_bits(const std::vector<ClipVertex>& a, const std::vector<ClipVertex>& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i) {
    const ClipVertex &x = a[i], &y = b[i];
    auto eq = [](const double* p, const double* q, int n) { return std::memcmp(p, q, sizeof(double) * n) == 0; };
    if (!eq(&x.position[0], &y.position[0], 4) || !eq(x.color.data(), y.color.data(), 4) ||
        !eq(x.secondary.data(), y.secondary.data(), 4))
      return false;
    for (int u = 0; u < kClipTexUnits; ++u)
      if (!eq(&x.texcoord[u][0], &y.texcoord[u][0], 4)) return false;
  }
  return true;
}

}  // namespace

TEST_CASE("clip shortcut: bit-identical to the six passes over random polygons") {
  std::mt19937_64 rng(20261123);
  std::uniform_real_distribution<double> attr(0, 1);
  // Spreads: well inside, straddling the planes, far outside, around w = 0.
  const double spreads[] = {0.5, 1.2, 4.0, 50.0};
  int inside = 0, outside = 0, clipped = 0;
  for (int c = 0; c < 20000; ++c) {
    const double spread = spreads[c % 4];
    std::uniform_real_distribution<double> pos(-spread, spread);
    std::vector<ClipVertex> poly(3 + static_cast<std::size_t>(rng() % 4));
    for (ClipVertex& v : poly) {
      const double w = (c % 7 == 0) ? pos(rng) : 1 + attr(rng);
      v.position = {pos(rng), pos(rng), pos(rng), w};
      if (c % 997 == 0) v.position.x = std::numeric_limits<double>::quiet_NaN();
      for (int k = 0; k < 4; ++k) {
        v.color[k] = attr(rng);
        v.secondary[k] = attr(rng);
      }
      for (int u = 0; u < kClipTexUnits; ++u) v.texcoord[u] = {attr(rng) * 8, attr(rng) * 8, 0, 1};
    }
    const auto fast = clip_polygon(poly), ref = clip_polygon_passes(poly);
    INFO("case " << c);
    REQUIRE(same_bits(fast, ref));
    bool all_in = true;
    for (const ClipVertex& v : poly) all_in = all_in && inside_view_volume(v.position);
    if (all_in) ++inside;
    else if (ref.empty()) ++outside;
    else ++clipped;
  }
  // Every branch was exercised (the counts depend only on the seed).
  CHECK(inside > 1000);
  CHECK(outside > 1000);
  CHECK(clipped > 1000);
  // The comparison can fail: a polygon that is clipped differs from its input.
  std::vector<ClipVertex> straddle(3);
  straddle[0].position = {-2, 0, 0, 1};
  straddle[1].position = {0.5, 0.5, 0, 1};
  straddle[2].position = {0.5, -0.5, 0, 1};
  CHECK_FALSE(same_bits(clip_polygon(straddle), straddle));
}
