// Scale and bias of RGBA components (GL121 §3.6.5 "Arithmetic on Components";
// also the post-convolution and post-colour-matrix scale/bias of the imaging
// subset): C' = C * scale + bias in the evaluation precision T, no clamp.
#pragma once
#include <array>

#include "pipeline/pixel_transfer/pixel_image.h"

namespace ffsim::pixel {

// True when every scale is 1 and every bias 0 (the stage cannot change a finite value).
bool is_identity_scale_bias(const std::array<double, 4>& scale, const std::array<double, 4>& bias);

template <class T>
void scale_bias(RgbaImage<T>& img, const std::array<double, 4>& scale, const std::array<double, 4>& bias);

}  // namespace ffsim::pixel
