// Image files through OpenImageIO: PNG (8/16-bit), TIFF, OpenEXR (float).
//
// In memory an Image keeps the file's samples exactly (8-bit and 16-bit codes as
// integers, float as binary32) with rows bottom to top, the order of GL client
// images and of the framebuffer. Every failure throws ImageError whose message
// starts with the file name.
#pragma once
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "sim/framebuffer.h"

namespace ffsim {

struct ImageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

enum class SampleType { U8, U16, F32 };

struct Image {
  int width = 0, height = 0, channels = 0;  // channels 1..4 (grey, grey+alpha, RGB, RGBA)
  SampleType type = SampleType::U8;
  std::vector<std::uint8_t> u8;    // used when type == U8
  std::vector<std::uint16_t> u16;  // used when type == U16
  std::vector<float> f32;          // used when type == F32

  static Image make(int width, int height, int channels, SampleType type);
  std::size_t index(int x, int y, int c) const {
    return (static_cast<std::size_t>(y) * width + x) * channels + c;
  }
  // Normalised value: code / (2^8-1) or code / (2^16-1), or the float itself.
  double value(int x, int y, int c) const;
  bool operator==(const Image&) const = default;
};

// Reads PNG/TIFF/EXR (anything OpenImageIO reads). 8-bit files give U8, 16-bit
// integer files U16, half/float/double files F32. Errors: missing or unreadable
// file, corrupt data, 0 or more than 4 channels, sizes beyond the framebuffer
// limits, non-finite float samples (the message names the first such pixel).
Image read_image(const std::string& path);

// Writes by extension: .png (U8 or U16; F32 is clamped to [0,1] and rounded to
// 16-bit codes), .exr (32-bit float; integer codes become code/max), .tif/.tiff
// (the image's own type). Unknown extensions and I/O failures throw ImageError.
void write_image(const std::string& path, const Image& img);

// Framebuffer contents as images (rows bottom to top like the framebuffer):
// fixed color of <= 8 bits becomes U8 (codes converted to 8 bits, exact at 8),
// wider fixed color U16, float color F32. Alpha alone is a 1-channel image.
Image color_image(const Framebuffer& fb);
Image alpha_image(const Framebuffer& fb);
// Stencil values unscaled as U8 grey (a 1-bit mask is 0/1); pass `stretch` to
// scale them to the full 8-bit range for viewing.
Image stencil_image(const Framebuffer& fb, bool stretch = false);
// Depth codes converted to 16-bit grey (U16).
Image depth_image(const Framebuffer& fb);

}  // namespace ffsim
