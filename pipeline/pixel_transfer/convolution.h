// Convolution (GL121 §3.6.5 "Convolution", Table 3.14; EXT_convolution): 1D, 2D
// and separable 2D filters with the border modes REDUCE, CONSTANT_BORDER and
// REPLICATE_BORDER. Sums of products in the evaluation precision T, no clamp.
#pragma once
#include "pipeline/pixel_transfer/pixel_image.h"
#include "pipeline/pixel_transfer/pixel_state.h"

namespace ffsim::pixel {

enum class FilterKind { OneD, TwoD, Separable };

// Builds filter taps from unpacked RGBA groups (GL121 §3.6.3 "Convolution Filter
// Specification"): each component c * CONVOLUTION_FILTER_SCALE + BIAS in T, no
// clamp; then the components of the filter's base format are kept and expanded
// to R, G, B, A slots (L -> R,G,B; I -> R,G,B,A; others 0).
template <class T>
std::vector<double> make_filter_taps(const RgbaImage<T>& groups, const ConvolutionFilter& f);

// Output size of convolving a width x height image (REDUCE shrinks by Wf-1,
// Hf-1; the other modes keep the size). Either may come out <= 0: the result is
// then empty (no error, GL121 §3.6.5).
void convolved_size(const ConvolutionFilter& f, FilterKind kind, int width, int height, int& out_w, int& out_h);

// The convolution. With Cw = floor(Wf/2), Ch = floor(Hf/2):
//   REDUCE:  C'(i,j) = sum_{n<Wf} sum_{m<Hf} C(i+n, j+m) F(n,m)
//   borders: C'(i,j) = sum_{n<Wf} sum_{m<Hf} C(i+n-Cw, j+m-Ch) F(n,m), where an
//            out-of-image C is the border colour (CONSTANT_BORDER) or the nearest
//            edge pixel (REPLICATE_BORDER).
// Separable: F(n,m) = Frow(n) Fcol(m), evaluated as (C * Frow(n)) * Fcol(m).
// Accumulation: one accumulator per component starting at 0, n outer, m inner,
// each product rounded then added (no FMA). Components the filter's base format
// does not convolve (Table 3.14) take the source value at the filter centre:
// C(i+Cw, j+Ch) under REDUCE, C(i,j) under the border modes.
template <class T>
RgbaImage<T> convolve(const RgbaImage<T>& img, const ConvolutionFilter& f, FilterKind kind);

}  // namespace ffsim::pixel
