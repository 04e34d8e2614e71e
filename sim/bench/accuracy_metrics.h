// The error measures of `ffsim bench`: what a variant's dumps say (lit mask,
// shadow factor, shaded image), the exact reference of one light, and the
// per-light numbers accumulated over the light sweep.
#pragma once
#include <string>
#include <vector>

#include "sim/bench/accuracy_config.h"
#include "sim/paper_run.h"

namespace ffsim::bench {

// One frame's shadow result, row-major, bottom row first.
struct Frame {
  int width = 0, height = 0;
  std::vector<bool> lit;         // true = lit
  std::vector<double> factor;    // shadow factor in [0, 1]
  std::vector<float> shaded;     // RGB, 3 per pixel, in [0, 1]
};

// The exact reference of one (scene, size, light): kautz-reference.trace's dumps.
struct ReferenceFrame {
  int width = 0, height = 0;
  std::vector<bool> covered;     // coverage.png alpha > 1/2
  Frame exact;                   // reference.png, factor = the 0/1 mask, shaded.png
  std::vector<double> soft;      // soft.png
  Frame ellipse;                 // ellipse.png, factor = mask, bump.png * mask
};

// Reads the reference run; throws std::runtime_error naming a missing dump.
ReferenceFrame reference_frame(const paper::Run& run);
// Reads a variant's run by its kind (Hard, AA); throws std::runtime_error naming a missing dump.
Frame variant_frame(const paper::Run& run, VariantKind kind);

// One light's error of a frame against a reference frame, over the covered pixels.
struct FrameError {
  long long pixels = 0, false_lit = 0, false_shadow = 0;
  double disagreement = 0;  // (false lit + false shadow) / pixels
  double shaded_rmse = 0;   // over R, G and B
  double factor_rmse = 0;   // against `soft` (when given)
  double worst = 0;         // max |shaded - reference shaded| over the channels
  int worst_x = -1, worst_y = -1;
};
FrameError frame_error(const Frame& f, const Frame& ref, const std::vector<bool>& covered,
                       const std::vector<double>* soft);

// Accumulates per-light errors and the timing of one table row.
struct RowAccumulator {
  int lights = 0;
  double sum_dis = 0, max_dis = -1, sum_shaded = 0, max_shaded = -1, sum_factor = 0, max_factor = -1;
  std::string worst_light;  // the light of max_dis
  double worst = -1;
  int worst_x = -1, worst_y = -1;
  std::string worst_pixel_light;
  int ideal_lights = 0;
  double sum_ideal_dis = 0, sum_ideal_shaded = 0, max_ideal_dis = -1;
  std::vector<double> seconds;  // timed replays
  bool ok = true;
  std::string error;

  void add(const FrameError& e, const std::string& light);
  void add_vs_ideal(const FrameError& e);
  void fail(const std::string& message);
};

// Median, minimum and maximum of v (NaN when empty).
struct Spread {
  double median, min, max;
};
Spread spread(std::vector<double> v);

}  // namespace ffsim::bench
