// Comparing two images sample by sample (`ffsim diff`, `ffsim compare`).
//
// Samples are compared as real values (code / (2^bits - 1) for 8- and 16-bit
// images, the float itself for float images), so an 8-bit PNG and the EXR of the
// same framebuffer compare equal. Differences are reported in LSBs of the coarser
// image: 8-bit when either image is 8-bit or float, else 16-bit.
#pragma once
#include <string>
#include <vector>

#include "sim/image_io.h"

namespace ffsim {

struct ImageDiff {
  bool same_shape = true;
  std::string shape_note;  // "sizes differ: 64x64 vs 32x32" when !same_shape
  int width = 0, height = 0, channels = 0;
  int lsb_bits = 8;                 // the LSB unit is 1 / (2^lsb_bits - 1)
  std::vector<double> max_lsb;      // per channel: max |a - b| in LSBs
  long long differing_pixels = 0;   // pixels where any channel differs
  long long total_pixels = 0;
  double rmse = 0;                  // over all samples, in real values
  double psnr = 0;                  // 20 log10(1 / rmse) dB; infinite when identical
  // Single-channel images (alpha, stencil, shadow masks): a pixel is lit when its
  // value is > 0 and in shadow when it is 0; pixels lit in one image and in
  // shadow in the other.
  bool is_mask = false;
  long long lit_shadow_disagreements = 0;
  Image heatmap;  // RGB 8-bit: black where equal, red -> yellow -> white with the difference
  bool identical() const { return same_shape && differing_pixels == 0; }
};

ImageDiff diff_images(const Image& a, const Image& b);

}  // namespace ffsim
