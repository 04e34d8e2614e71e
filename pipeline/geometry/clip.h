// Primitive clipping (GL121 §2.11): a convex polygon in clip coordinates is
// clipped against the view volume -w <= x, y, z <= w. Every attribute of a new
// vertex is interpolated linearly in clip space with the same parameter t as the
// position (eq. 2.6), which keeps texture coordinates perspective-correct.
//
// Clipping against all six planes also bounds every vertex's window coordinates
// to the viewport, so the rasterizer's integer range ("guard band") is never
// exceeded, and a polygon partly behind the eye (w <= 0) keeps exactly its part
// in front of the near plane.
#pragma once
#include <array>
#include <vector>

#include <glm/vec4.hpp>

namespace ffsim {

inline constexpr int kClipTexUnits = 4;

struct ClipVertex {
  glm::dvec4 position{0, 0, 0, 1};           // clip coordinates
  std::array<double, 4> color{1, 1, 1, 1};   // primary colour, clamped to [0,1]
  std::array<double, 4> secondary{0, 0, 0, 0};
  std::array<glm::dvec4, kClipTexUnits> texcoord{};  // after the texture matrix
};

// Sutherland-Hodgman against x = ±w, y = ±w, z = ±w in that order. The new
// vertex on an edge is computed from the edge's inside endpoint, so an edge
// shared by two polygons yields the same vertex in both. Returns fewer than 3
// vertices when nothing remains.
std::vector<ClipVertex> clip_polygon(std::vector<ClipVertex> poly);
// The six passes alone, without clip_polygon's shortcut for polygons wholly inside
// the view volume or wholly outside one plane (the reference its tests compare with).
std::vector<ClipVertex> clip_polygon_passes(std::vector<ClipVertex> poly);

// Whether a point lies in the view volume (raster position validity, §2.12).
bool inside_view_volume(const glm::dvec4& p);

}  // namespace ffsim
