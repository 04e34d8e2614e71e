#include "pipeline/pixel_transfer/transfer_plan.h"

#include <algorithm>

#include "pipeline/pixel_transfer/color_table.h"
#include "pipeline/pixel_transfer/pixel_map.h"
#include "pipeline/pixel_transfer/scale_bias.h"

namespace ffsim::pixel {

const char* stage_name(Stage s) {
  switch (s) {
    case Stage::ScaleBias: return "scale_bias";
    case Stage::MapColor: return "map_color";
    case Stage::ColorTable: return "color_table";
    case Stage::Convolution: return "convolution";
    case Stage::PostConvolutionScaleBias: return "post_convolution_scale_bias";
    case Stage::PostConvolutionColorTable: return "post_convolution_color_table";
    case Stage::ColorMatrix: return "color_matrix";
    case Stage::PostColorMatrixScaleBias: return "post_color_matrix_scale_bias";
    case Stage::PostColorMatrixColorTable: return "post_color_matrix_color_table";
  }
  return "?";
}

bool TransferPlan::has(Stage s) const { return std::find(stages.begin(), stages.end(), s) != stages.end(); }

namespace {
const char* base_name(BaseFormat b) {
  switch (b) {
    case BaseFormat::Alpha: return "ALPHA";
    case BaseFormat::Luminance: return "LUMINANCE";
    case BaseFormat::LuminanceAlpha: return "LUMINANCE_ALPHA";
    case BaseFormat::Intensity: return "INTENSITY";
    case BaseFormat::RGB: return "RGB";
    case BaseFormat::RGBA: return "RGBA";
  }
  return "?";
}
const char* kind_name(FilterKind k) {
  switch (k) {
    case FilterKind::OneD: return "1D";
    case FilterKind::TwoD: return "2D";
    case FilterKind::Separable: return "separable";
  }
  return "?";
}
const char* border_name(BorderMode m) {
  switch (m) {
    case BorderMode::Reduce: return "REDUCE";
    case BorderMode::ConstantBorder: return "CONSTANT_BORDER";
    case BorderMode::ReplicateBorder: return "REPLICATE_BORDER";
  }
  return "?";
}
std::string table_str(const ColorTable& t) {
  return std::string("(") + base_name(t.base) + ", " + std::to_string(t.width) + ")";
}
}  // namespace

const ConvolutionFilter* active_filter(const ImagingState& s, ImageDims dims, FilterKind* kind) {
  // A filter that was never specified (width 0) convolves nothing (docs/numerics.md §7).
  if (dims == ImageDims::OneD) {
    if (s.conv1d.enabled && s.conv1d.width > 0) {
      if (kind) *kind = FilterKind::OneD;
      return &s.conv1d;
    }
    return nullptr;
  }
  if (s.conv2d.enabled && s.conv2d.width > 0) {
    if (kind) *kind = FilterKind::TwoD;
    return &s.conv2d;
  }
  if (s.separable2d.enabled && s.separable2d.width > 0) {
    if (kind) *kind = FilterKind::Separable;
    return &s.separable2d;
  }
  return nullptr;
}

std::string TransferPlan::str(const TransferInputs& in) const {
  if (stages.empty()) return "identity";
  std::string s;
  for (Stage st : stages) {
    if (!s.empty()) s += " -> ";
    s += stage_name(st);
    switch (st) {
      case Stage::ColorTable: s += table_str(in.imaging.table(TableSlot::Color)); break;
      case Stage::PostConvolutionColorTable: s += table_str(in.imaging.table(TableSlot::PostConvolution)); break;
      case Stage::PostColorMatrixColorTable: s += table_str(in.imaging.table(TableSlot::PostColorMatrix)); break;
      case Stage::Convolution: {
        FilterKind k = filter_kind;
        const ConvolutionFilter* f = nullptr;
        switch (k) {
          case FilterKind::OneD: f = &in.imaging.conv1d; break;
          case FilterKind::TwoD: f = &in.imaging.conv2d; break;
          case FilterKind::Separable: f = &in.imaging.separable2d; break;
        }
        s += std::string("(") + kind_name(k) + " " + std::to_string(f->width) + "x" +
             std::to_string(k == FilterKind::OneD ? 1 : f->height) + ", " + base_name(f->base) + ", " +
             border_name(f->border_mode) + ")";
        break;
      }
      default: break;
    }
  }
  return s;
}

TransferPlan plan_transfer(const TransferInputs& in, ImageDims dims) {
  TransferPlan p;
  const PixelTransferState& t = in.transfer;
  if (!is_identity_scale_bias(t.scale, t.bias)) p.stages.push_back(Stage::ScaleBias);
  if (t.map_color) p.stages.push_back(Stage::MapColor);
  if (table_active(in.imaging.table(TableSlot::Color))) p.stages.push_back(Stage::ColorTable);
  if (active_filter(in.imaging, dims, &p.filter_kind)) {
    p.stages.push_back(Stage::Convolution);
    if (!is_identity_scale_bias(t.post_convolution_scale, t.post_convolution_bias))
      p.stages.push_back(Stage::PostConvolutionScaleBias);
  }
  if (table_active(in.imaging.table(TableSlot::PostConvolution))) p.stages.push_back(Stage::PostConvolutionColorTable);
  if (!is_identity_matrix(in.color_matrix)) p.stages.push_back(Stage::ColorMatrix);
  else if (!is_identity_scale_bias(t.post_color_matrix_scale, t.post_color_matrix_bias))
    p.stages.push_back(Stage::PostColorMatrixScaleBias);
  if (table_active(in.imaging.table(TableSlot::PostColorMatrix))) p.stages.push_back(Stage::PostColorMatrixColorTable);
  return p;
}

template <class T>
RgbaImage<T> run_plan(const TransferPlan& plan, const TransferInputs& in, RgbaImage<T> img) {
  const PixelTransferState& t = in.transfer;
  for (Stage st : plan.stages) {
    switch (st) {
      case Stage::ScaleBias: scale_bias(img, t.scale, t.bias); break;
      case Stage::MapColor: map_color(img, t.color_maps); break;
      case Stage::ColorTable: color_table_lookup(img, in.imaging.table(TableSlot::Color)); break;
      case Stage::Convolution: {
        FilterKind k = plan.filter_kind;
        const ConvolutionFilter* f = k == FilterKind::OneD   ? &in.imaging.conv1d
                                     : k == FilterKind::TwoD ? &in.imaging.conv2d
                                                             : &in.imaging.separable2d;
        img = convolve(img, *f, k);
        break;
      }
      case Stage::PostConvolutionScaleBias: scale_bias(img, t.post_convolution_scale, t.post_convolution_bias); break;
      case Stage::PostConvolutionColorTable:
        color_table_lookup(img, in.imaging.table(TableSlot::PostConvolution));
        break;
      case Stage::ColorMatrix:
        color_matrix(img, in.color_matrix, t.post_color_matrix_scale, t.post_color_matrix_bias);
        break;
      case Stage::PostColorMatrixScaleBias:
        scale_bias(img, t.post_color_matrix_scale, t.post_color_matrix_bias);
        break;
      case Stage::PostColorMatrixColorTable:
        color_table_lookup(img, in.imaging.table(TableSlot::PostColorMatrix));
        break;
    }
  }
  return img;
}

template <class T>
RgbaImage<T> run_every_stage(const TransferInputs& in, ImageDims dims, RgbaImage<T> img) {
  const PixelTransferState& t = in.transfer;
  scale_bias(img, t.scale, t.bias);
  if (t.map_color) map_color(img, t.color_maps);
  color_table_lookup(img, in.imaging.table(TableSlot::Color));
  FilterKind k = FilterKind::TwoD;
  if (const ConvolutionFilter* f = active_filter(in.imaging, dims, &k)) {
    img = convolve(img, *f, k);
    // Choice #9: post-convolution scale/bias only when a convolution was applied.
    scale_bias(img, t.post_convolution_scale, t.post_convolution_bias);
  }
  color_table_lookup(img, in.imaging.table(TableSlot::PostConvolution));
  color_matrix(img, in.color_matrix, t.post_color_matrix_scale, t.post_color_matrix_bias);
  color_table_lookup(img, in.imaging.table(TableSlot::PostColorMatrix));
  return img;
}

void transfer_output_size(const TransferInputs& in, ImageDims dims, int width, int height, int& out_w, int& out_h) {
  FilterKind k = FilterKind::TwoD;
  if (const ConvolutionFilter* f = active_filter(in.imaging, dims, &k)) {
    convolved_size(*f, k, width, height, out_w, out_h);
    if (out_w < 0) out_w = 0;
    if (out_h < 0) out_h = 0;
    return;
  }
  out_w = width;
  out_h = height;
}

template RgbaImage<float> run_plan<float>(const TransferPlan&, const TransferInputs&, RgbaImage<float>);
template RgbaImage<double> run_plan<double>(const TransferPlan&, const TransferInputs&, RgbaImage<double>);
template RgbaImage<float> run_every_stage<float>(const TransferInputs&, ImageDims, RgbaImage<float>);
template RgbaImage<double> run_every_stage<double>(const TransferInputs&, ImageDims, RgbaImage<double>);

}  // namespace ffsim::pixel
