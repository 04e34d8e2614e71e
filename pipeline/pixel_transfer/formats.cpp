#include "pipeline/pixel_transfer/formats.h"

namespace ffsim::pixel {

int color_format_components(GLenum format) {
  switch (format) {
    case gl::RED:
    case gl::GREEN:
    case gl::BLUE:
    case gl::ALPHA:
    case gl::LUMINANCE: return 1;
    case gl::LUMINANCE_ALPHA: return 2;
    case gl::RGB:
    case gl::BGR: return 3;
    case gl::RGBA:
    case gl::BGRA: return 4;
    default: return 0;
  }
}

int type_size(GLenum type) {
  switch (type) {
    case gl::UNSIGNED_BYTE:
    case gl::BYTE: return 1;
    case gl::UNSIGNED_SHORT:
    case gl::SHORT: return 2;
    case gl::UNSIGNED_INT:
    case gl::INT:
    case gl::FLOAT: return 4;
    default: return 0;
  }
}

bool is_unsupported_gl_type(GLenum type) {
  // BITMAP (0x1A00) and the packed types of GL 1.2 (0x8032..0x8036, 0x8362..0x8368).
  return type == gl::BITMAP || (type >= 0x8032 && type <= 0x8036) || (type >= 0x8362 && type <= 0x8368);
}

namespace {
std::optional<InternalFormat> sized_or_base(GLenum f) {
  using B = BaseFormat;
  switch (f) {
    case gl::ALPHA: return InternalFormat{B::Alpha, 0};
    case gl::ALPHA4: return InternalFormat{B::Alpha, 4};
    case gl::ALPHA8: return InternalFormat{B::Alpha, 8};
    case gl::ALPHA12: return InternalFormat{B::Alpha, 12};
    case gl::ALPHA16: return InternalFormat{B::Alpha, 16};
    case gl::LUMINANCE: return InternalFormat{B::Luminance, 0};
    case gl::LUMINANCE4: return InternalFormat{B::Luminance, 4};
    case gl::LUMINANCE8: return InternalFormat{B::Luminance, 8};
    case gl::LUMINANCE12: return InternalFormat{B::Luminance, 12};
    case gl::LUMINANCE16: return InternalFormat{B::Luminance, 16};
    case gl::LUMINANCE_ALPHA: return InternalFormat{B::LuminanceAlpha, 0};
    case gl::LUMINANCE4_ALPHA4: return InternalFormat{B::LuminanceAlpha, 4};
    case gl::LUMINANCE6_ALPHA2: return InternalFormat{B::LuminanceAlpha, 6, {6, 2, 0, 0}};
    case gl::LUMINANCE8_ALPHA8: return InternalFormat{B::LuminanceAlpha, 8};
    case gl::LUMINANCE12_ALPHA4: return InternalFormat{B::LuminanceAlpha, 12, {12, 4, 0, 0}};
    case gl::LUMINANCE12_ALPHA12: return InternalFormat{B::LuminanceAlpha, 12};
    case gl::LUMINANCE16_ALPHA16: return InternalFormat{B::LuminanceAlpha, 16};
    case gl::INTENSITY: return InternalFormat{B::Intensity, 0};
    case gl::INTENSITY4: return InternalFormat{B::Intensity, 4};
    case gl::INTENSITY8: return InternalFormat{B::Intensity, 8};
    case gl::INTENSITY12: return InternalFormat{B::Intensity, 12};
    case gl::INTENSITY16: return InternalFormat{B::Intensity, 16};
    case gl::RGB: return InternalFormat{B::RGB, 0};
    case gl::R3_G3_B2: return InternalFormat{B::RGB, 6, {3, 3, 2, 0}};  // lcm(3, 2) = 6
    case gl::RGB4: return InternalFormat{B::RGB, 4};
    case gl::RGB5: return InternalFormat{B::RGB, 5};
    case gl::RGB8: return InternalFormat{B::RGB, 8};
    case gl::RGB10: return InternalFormat{B::RGB, 10};
    case gl::RGB12: return InternalFormat{B::RGB, 12};
    case gl::RGB16: return InternalFormat{B::RGB, 16};
    case gl::RGBA: return InternalFormat{B::RGBA, 0};
    case gl::RGBA2: return InternalFormat{B::RGBA, 2};
    case gl::RGBA4: return InternalFormat{B::RGBA, 4};
    case gl::RGB5_A1: return InternalFormat{B::RGBA, 5, {5, 5, 5, 1}};
    case gl::RGBA8: return InternalFormat{B::RGBA, 8};
    case gl::RGB10_A2: return InternalFormat{B::RGBA, 10, {10, 10, 10, 2}};
    case gl::RGBA12: return InternalFormat{B::RGBA, 12};
    case gl::RGBA16: return InternalFormat{B::RGBA, 16};
    default: return std::nullopt;
  }
}
}  // namespace

std::optional<InternalFormat> texture_internal_format(GLenum f) {
  switch (f) {
    case 1: return InternalFormat{BaseFormat::Luminance, 0};
    case 2: return InternalFormat{BaseFormat::LuminanceAlpha, 0};
    case 3: return InternalFormat{BaseFormat::RGB, 0};
    case 4: return InternalFormat{BaseFormat::RGBA, 0};
    default: return sized_or_base(f);
  }
}

std::optional<InternalFormat> table_internal_format(GLenum f) { return sized_or_base(f); }

}  // namespace ffsim::pixel
