// The paper's scenes and the main job's report (issue 8): the terrain mesh of
// traces/include/terrain-mesh*.trace, the comparison of a variant's shadow images
// with the exact references, and the report over every trace and scene
// (`ffsim paper-mesh`, `ffsim paper-report`, sim/cli/cmd_paper.cpp).
#pragma once
#include <cstdint>
#include <iosfwd>
#include <string>
#include <utility>
#include <vector>

#include "sim/image_io.h"

namespace ffsim::paper {

// The terrain of the paper's figures 6.4-6.5: kTerrainGrid x kTerrainGrid vertices
// over the unit square, heights from the fractal field kTerrainField (texel units
// of a kTerrainRes field, divided by kTerrainRes: world units).
inline constexpr int kTerrainGrid = 31;
inline constexpr int kTerrainRes = 128;
inline constexpr const char* kTerrainField = "fractal w=128 seed=7 scale=4";

// World height of the terrain at texture coordinates (s, t): the field's bilinear
// surface at texel coordinates (s * 128 - 1/2, t * 128 - 1/2) (texel i's centre is
// s = (i + 1/2) / 128), divided by 128.
double terrain_height(double s, double t);

// The text of traces/include/terrain-mesh.trace (lit = false) or
// terrain-mesh-lit.trace (lit = true: the per-vertex light colour before each vertex).
std::string terrain_mesh_trace(bool lit);

// Lit/shadow classification of one variant against a reference, over the covered pixels.
struct ShadowStats {
  long long pixels = 0;        // covered pixels compared
  long long false_lit = 0;     // variant lit, reference shadow
  long long false_shadow = 0;  // variant shadow, reference lit
  double disagreement() const {
    return pixels ? static_cast<double>(false_lit + false_shadow) / static_cast<double>(pixels) : 0.0;
  }
};

// lit and reference: one value per pixel (row-major), true = lit; covered selects pixels.
ShadowStats compare_masks(const std::vector<bool>& lit, const std::vector<bool>& reference,
                          const std::vector<bool>& covered);
// RMSE of a against b over the covered pixels (values in [0, 1]).
double rmse(const std::vector<double>& a, const std::vector<double>& b, const std::vector<bool>& covered);

// Channel 0 of an image as values in [0, 1] (row-major, bottom row first).
std::vector<double> channel_values(const Image& im, int channel = 0);

struct ReportOptions {
  std::string traces_dir = "traces";
  std::string out_dir = "out";
  std::vector<std::pair<std::string, std::string>> sets;  // applied to every run (NAME, EXPR)
  bool quick = false;  // small resolutions (tests, smoke runs)
  int threads = 1;
};

// Replays every variant for every scene, writes OUT/<scene>/<variant>/ dumps,
// OUT/report.md and OUT/report.json. Returns 0 when every run succeeded.
int run_report(const ReportOptions& o, std::ostream& out, std::ostream& err);

}  // namespace ffsim::paper
