#include "pipeline/geometry/clip.h"

namespace ffsim {

namespace {

// Signed distance to plane k (>= 0 inside): k = 0..5 for w+x, w-x, w+y, w-y, w+z, w-z.
double plane_distance(const glm::dvec4& p, int k) {
  const double c = p[k / 2];
  return (k % 2 == 0) ? p.w + c : p.w - c;
}

ClipVertex lerp(const ClipVertex& in, const ClipVertex& out, double t) {
  // P = in + t·(out − in) for every attribute (GL121 eq. 2.6 with the roles named).
  ClipVertex v;
  v.position = in.position + t * (out.position - in.position);
  for (int c = 0; c < 4; ++c) {
    v.color[c] = in.color[c] + t * (out.color[c] - in.color[c]);
    v.secondary[c] = in.secondary[c] + t * (out.secondary[c] - in.secondary[c]);
  }
  for (int u = 0; u < kClipTexUnits; ++u) v.texcoord[u] = in.texcoord[u] + t * (out.texcoord[u] - in.texcoord[u]);
  return v;
}

}  // namespace

std::vector<ClipVertex> clip_polygon(std::vector<ClipVertex> poly) {
  // Trivial cases first, with the same outcome as the six passes below: a polygon
  // with every vertex inside every plane goes through each pass unchanged (each
  // edge keeps its inside start point, no edge crosses), and one with every vertex
  // outside the same plane loses every vertex in that pass.
  unsigned inside_all = 0x3f;
  for (const ClipVertex& v : poly) {
    unsigned inside = 0;
    for (int k = 0; k < 6; ++k)
      if (plane_distance(v.position, k) >= 0) inside |= 1u << k;
    inside_all &= inside;
  }
  if (inside_all == 0x3f) {
    if (poly.size() < 3) poly.clear();
    return poly;
  }
  bool outside_one = false;
  for (int k = 0; k < 6 && !outside_one; ++k) {
    outside_one = true;
    for (const ClipVertex& v : poly) outside_one = outside_one && !(plane_distance(v.position, k) >= 0);
  }
  if (outside_one) return {};
  return clip_polygon_passes(std::move(poly));
}

std::vector<ClipVertex> clip_polygon_passes(std::vector<ClipVertex> poly) {
  std::vector<ClipVertex> next;
  for (int k = 0; k < 6 && poly.size() >= 3; ++k) {
    next.clear();
    const std::size_t n = poly.size();
    for (std::size_t i = 0; i < n; ++i) {
      const ClipVertex& a = poly[i];
      const ClipVertex& b = poly[(i + 1) % n];
      const double da = plane_distance(a.position, k), db = plane_distance(b.position, k);
      const bool ia = da >= 0, ib = db >= 0;
      if (ia) next.push_back(a);
      if (ia != ib) {
        // t from the inside endpoint towards the outside one.
        next.push_back(ia ? lerp(a, b, da / (da - db)) : lerp(b, a, db / (db - da)));
      }
    }
    poly.swap(next);
  }
  if (poly.size() < 3) poly.clear();
  return poly;
}

bool inside_view_volume(const glm::dvec4& p) {
  if (!(p.w > 0)) return false;  // w = 0 has no window position
  for (int k = 0; k < 6; ++k)
    if (!(plane_distance(p, k) >= 0)) return false;
  return true;
}

}  // namespace ffsim
