// The transfer plan: the ordered list of pixel-transfer stages that do something
// for the current state (GL121 §3.6.5 order, spec-notes §2.1). Identity scale and
// bias, a disabled MAP_COLOR, disabled or empty colour tables, disabled or empty
// convolution filters and an identity colour matrix with identity post scale and
// bias drop out. Running the plan gives the same bits as running every stage
// (run_every_stage) for finite input; tests/pipeline/test_pixel_plan.cpp checks it.
#pragma once
#include <string>
#include <vector>

#include "pipeline/pixel_transfer/color_matrix.h"
#include "pipeline/pixel_transfer/convolution.h"
#include "pipeline/pixel_transfer/pixel_image.h"
#include "pipeline/pixel_transfer/pixel_state.h"

namespace ffsim::pixel {

enum class Stage {
  ScaleBias,                  // RED_SCALE .. ALPHA_BIAS
  MapColor,                   // PIXEL_MAP_R_TO_R .. A_TO_A
  ColorTable,                 // COLOR_TABLE
  Convolution,                // CONVOLUTION_1D / CONVOLUTION_2D / SEPARABLE_2D
  PostConvolutionScaleBias,   // POST_CONVOLUTION_x_SCALE/BIAS (only with a convolution)
  PostConvolutionColorTable,  // POST_CONVOLUTION_COLOR_TABLE
  ColorMatrix,                // colour matrix with its post scale/bias
  PostColorMatrixScaleBias,   // post-colour-matrix scale/bias alone (matrix is identity)
  PostColorMatrixColorTable,  // POST_COLOR_MATRIX_COLOR_TABLE
};
const char* stage_name(Stage s);

// The dimensionality of the image: 1D images (TexImage1D, CopyTexImage1D,
// TexSubImage1D, CopyTexSubImage1D) use CONVOLUTION_1D; all others the 2D filter,
// or the separable one when CONVOLUTION_2D is disabled.
enum class ImageDims { OneD, TwoD };

struct TransferInputs {
  const PixelTransferState& transfer;
  const ImagingState& imaging;
  Matrix4 color_matrix;  // top of the COLOR stack, column-major
};

struct TransferPlan {
  std::vector<Stage> stages;
  FilterKind filter_kind = FilterKind::TwoD;  // meaningful when Convolution is present
  bool has(Stage s) const;
  bool empty() const { return stages.empty(); }
  // "scale_bias -> color_matrix -> post_color_matrix_color_table(ALPHA, 4096)", or "identity".
  std::string str(const TransferInputs& in) const;
};

// The convolution filter that applies to an image of `dims`, or nullptr.
const ConvolutionFilter* active_filter(const ImagingState& s, ImageDims dims, FilterKind* kind);

TransferPlan plan_transfer(const TransferInputs& in, ImageDims dims);

template <class T>
RgbaImage<T> run_plan(const TransferPlan& plan, const TransferInputs& in, RgbaImage<T> img);

// Reference: every stage function called in spec order whether or not it can
// change anything (a disabled table or map stage is a no-op by definition).
template <class T>
RgbaImage<T> run_every_stage(const TransferInputs& in, ImageDims dims, RgbaImage<T> img);

// Output size of the transfer path for a width x height input (REDUCE convolution shrinks it).
void transfer_output_size(const TransferInputs& in, ImageDims dims, int width, int height, int& out_w, int& out_h);

}  // namespace ffsim::pixel
