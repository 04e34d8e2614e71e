// Texture storage shared by the pixel path (glTexImage*, glCopyTexImage*, which
// write levels) and texturing (which samples them). GL 1.2.1 §3.8.
#pragma once
#include <array>
#include <cstdint>
#include <vector>

#include "pipeline/gl/enums.h"

namespace ffsim {

// Base internal formats (GL121 Table 3.15) and their stored components, in order:
// ALPHA: A; LUMINANCE: L; LUMINANCE_ALPHA: L, A; INTENSITY: I; RGB: R, G, B;
// RGBA: R, G, B, A.
enum class BaseFormat { Alpha, Luminance, LuminanceAlpha, Intensity, RGB, RGBA };
constexpr int component_count(BaseFormat f) {
  switch (f) {
    case BaseFormat::Alpha:
    case BaseFormat::Luminance:
    case BaseFormat::Intensity: return 1;
    case BaseFormat::LuminanceAlpha: return 2;
    case BaseFormat::RGB: return 3;
    case BaseFormat::RGBA: return 4;
  }
  return 4;
}

// One mipmap level.
struct TextureImage {
  int width = 0;   // texels per row, border texels included (w_s + 2*border)
  int height = 0;  // rows, border included; 1 for 1D textures
  int border = 0;  // 0 or 1
  GLenum internal_format = 0;  // as requested (GL_RGBA8, GL_LUMINANCE, 4 (legacy), ...)
  BaseFormat base = BaseFormat::RGBA;
  int bits = 8;  // bits per stored component (fixed profiles)
  // Texels row-major from row 0 (t = 0 side, border row first when border = 1),
  // component_count(base) components per texel in the order above.
  std::vector<std::uint16_t> codes;  // fixed profiles: codes at `bits`
  std::vector<double> values;        // float profiles: values in [0,1]
  bool empty() const { return width == 0 || height == 0; }
};

// Texture parameters with their GL 1.2.1 initial values (Table 6.15).
struct TextureParams {
  GLenum min_filter = gl::NEAREST_MIPMAP_LINEAR;
  GLenum mag_filter = gl::LINEAR;
  GLenum wrap_s = gl::REPEAT;
  GLenum wrap_t = gl::REPEAT;
  std::array<double, 4> border_color{0, 0, 0, 0};  // clamped to [0,1] when set
  double min_lod = -1000, max_lod = 1000;
  int base_level = 0, max_level = 1000;
  double priority = 1.0;
};

struct TextureObject {
  GLenum target = 0;  // TEXTURE_1D or TEXTURE_2D once bound/specified; 0 before
  std::vector<TextureImage> levels;  // index = level of detail
  TextureParams params;
  // Bumped whenever levels or params change, so caches keyed on a texture can tell.
  std::uint64_t version = 0;
};

}  // namespace ffsim
