#include "sim/image_io.h"

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "pipeline/number/unorm.h"

namespace ffsim {

namespace {

std::string lower_ext(const std::string& path) {
  std::string e = std::filesystem::path(path).extension().string();
  std::transform(e.begin(), e.end(), e.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return e;
}

[[noreturn]] void fail(const std::string& path, const std::string& why) { throw ImageError(path + ": " + why); }

// OpenImageIO rows are top to bottom; ours are bottom to top.
template <class T>
void flip_rows(std::vector<T>& v, int width, int height, int channels) {
  if (v.empty()) return;  // the sample vectors of the other types are empty
  const std::size_t row = static_cast<std::size_t>(width) * channels;
  for (int y = 0; y < height / 2; ++y)
    std::swap_ranges(v.begin() + y * row, v.begin() + (y + 1) * row, v.begin() + (height - 1 - y) * row);
}

}  // namespace

Image Image::make(int width, int height, int channels, SampleType type) {
  Image im;
  im.width = width;
  im.height = height;
  im.channels = channels;
  im.type = type;
  const std::size_t n = static_cast<std::size_t>(width) * height * channels;
  if (type == SampleType::U8) im.u8.assign(n, 0);
  if (type == SampleType::U16) im.u16.assign(n, 0);
  if (type == SampleType::F32) im.f32.assign(n, 0.0f);
  return im;
}

double Image::value(int x, int y, int c) const {
  const std::size_t i = index(x, y, c);
  switch (type) {
    case SampleType::U8: return unorm_to_double(u8[i], 8);
    case SampleType::U16: return unorm_to_double(u16[i], 16);
    case SampleType::F32: return f32[i];
  }
  return 0.0;
}

Image read_image(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) fail(path, "no such file");
  if (std::filesystem::is_directory(path, ec)) fail(path, "is a directory, expected an image file");
  // Keep samples exactly as stored: no premultiplication of color by alpha.
  OIIO::ImageSpec config;
  config.attribute("oiio:UnassociatedAlpha", 1);
  auto in = OIIO::ImageInput::open(path, &config);
  if (!in) fail(path, "cannot read as an image (" + OIIO::geterror() + ")");
  const OIIO::ImageSpec spec = in->spec();
  if (spec.width <= 0 || spec.height <= 0) fail(path, "empty image");
  if (spec.width > kMaxFramebufferSide || spec.height > kMaxFramebufferSide ||
      static_cast<long long>(spec.width) * spec.height > kMaxFramebufferPixels)
    fail(path, "size " + std::to_string(spec.width) + "x" + std::to_string(spec.height) +
                   " exceeds the limit (16384 per side, 2^26 pixels)");
  if (spec.nchannels < 1 || spec.nchannels > 4)
    fail(path, std::to_string(spec.nchannels) + " channels; expected 1 to 4");
  if (spec.depth > 1) fail(path, "volume images are not supported");
  SampleType type = SampleType::F32;
  const auto base = spec.format.basetype;
  if (base == OIIO::TypeDesc::UINT8 || base == OIIO::TypeDesc::INT8) type = SampleType::U8;
  else if (base == OIIO::TypeDesc::UINT16 || base == OIIO::TypeDesc::INT16) type = SampleType::U16;
  else if (base == OIIO::TypeDesc::UINT32 || base == OIIO::TypeDesc::INT32) type = SampleType::U16;
  Image im = Image::make(spec.width, spec.height, spec.nchannels, type);
  bool ok = false;
  switch (type) {
    case SampleType::U8: ok = in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::UINT8, im.u8.data()); break;
    case SampleType::U16: ok = in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::UINT16, im.u16.data()); break;
    case SampleType::F32: ok = in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, im.f32.data()); break;
  }
  if (!ok) fail(path, "corrupt or truncated image data (" + in->geterror() + ")");
  in->close();
  if (type == SampleType::F32) {
    for (std::size_t i = 0; i < im.f32.size(); ++i)
      if (!std::isfinite(im.f32[i])) {
        const std::size_t px = i / spec.nchannels;
        fail(path, "non-finite sample (" + std::string(std::isnan(im.f32[i]) ? "NaN" : "Inf") + ") at pixel x=" +
                       std::to_string(px % spec.width) + " y=" + std::to_string(px / spec.width) +
                       " (top-left origin), channel " + std::to_string(i % spec.nchannels));
      }
  }
  flip_rows(im.u8, im.width, im.height, im.channels);
  flip_rows(im.u16, im.width, im.height, im.channels);
  flip_rows(im.f32, im.width, im.height, im.channels);
  return im;
}

void write_image(const std::string& path, const Image& img0) {
  const std::string ext = lower_ext(path);
  if (ext != ".png" && ext != ".exr" && ext != ".tif" && ext != ".tiff")
    fail(path, "unsupported output extension `" + ext + "` (expected .png, .exr, .tif)");
  if (img0.width <= 0 || img0.height <= 0 || img0.channels < 1 || img0.channels > 4)
    fail(path, "nothing to write (empty image)");
  Image img = img0;
  // Convert to what the container stores.
  if (ext == ".exr" && img.type != SampleType::F32) {
    Image f = Image::make(img.width, img.height, img.channels, SampleType::F32);
    for (int y = 0; y < img.height; ++y)
      for (int x = 0; x < img.width; ++x)
        for (int c = 0; c < img.channels; ++c) f.f32[f.index(x, y, c)] = static_cast<float>(img.value(x, y, c));
    img = std::move(f);
  } else if (ext == ".png" && img.type == SampleType::F32) {
    Image u = Image::make(img.width, img.height, img.channels, SampleType::U16);
    for (std::size_t i = 0; i < img.f32.size(); ++i)
      u.u16[i] = static_cast<std::uint16_t>(unorm_from_double(img.f32[i], 16));
    img = std::move(u);
  }
  flip_rows(img.u8, img.width, img.height, img.channels);
  flip_rows(img.u16, img.width, img.height, img.channels);
  flip_rows(img.f32, img.width, img.height, img.channels);
  const OIIO::TypeDesc td = img.type == SampleType::U8    ? OIIO::TypeDesc::UINT8
                            : img.type == SampleType::U16 ? OIIO::TypeDesc::UINT16
                                                          : OIIO::TypeDesc::FLOAT;
  const void* data = img.type == SampleType::U8    ? static_cast<const void*>(img.u8.data())
                     : img.type == SampleType::U16 ? static_cast<const void*>(img.u16.data())
                                                   : static_cast<const void*>(img.f32.data());
  std::error_code ec;
  const auto parent = std::filesystem::path(path).parent_path();
  if (!parent.empty() && !std::filesystem::is_directory(parent, ec))
    fail(path, "output directory " + parent.string() + " does not exist");
  auto out = OIIO::ImageOutput::create(path);
  if (!out) fail(path, "cannot create writer (" + OIIO::geterror() + ")");
  OIIO::ImageSpec spec(img.width, img.height, img.channels, td);
  if (img.channels == 2) spec.alpha_channel = 1;
  spec.attribute("oiio:UnassociatedAlpha", 1);  // our alpha is not premultiplied
  if (!out->open(path, spec)) fail(path, "cannot open for writing (" + out->geterror() + ")");
  if (!out->write_image(td, data)) fail(path, "write failed (" + out->geterror() + ")");
  if (!out->close()) fail(path, "close failed (" + out->geterror() + ")");
}

namespace {
Image channels_image(const Framebuffer& fb, int first, int count) {
  const auto& f = fb.format();
  const SampleType t = f.float_color() ? SampleType::F32 : (f.color_bits <= 8 ? SampleType::U8 : SampleType::U16);
  Image im = Image::make(fb.width(), fb.height(), count, t);
  for (int y = 0; y < fb.height(); ++y)
    for (int x = 0; x < fb.width(); ++x)
      for (int c = 0; c < count; ++c) {
        const std::size_t src = 4 * fb.index(x, y) + first + c, dst = im.index(x, y, c);
        if (t == SampleType::F32) im.f32[dst] = static_cast<float>(fb.values()[src]);
        else if (t == SampleType::U8) im.u8[dst] = static_cast<std::uint8_t>(unorm_convert(fb.codes()[src], f.color_bits, 8));
        else im.u16[dst] = static_cast<std::uint16_t>(unorm_convert(fb.codes()[src], f.color_bits, 16));
      }
  return im;
}
}  // namespace

Image color_image(const Framebuffer& fb) { return channels_image(fb, 0, 4); }
Image alpha_image(const Framebuffer& fb) { return channels_image(fb, 3, 1); }

Image stencil_image(const Framebuffer& fb, bool stretch) {
  if (!fb.has_stencil()) throw FramebufferError("the framebuffer has no stencil buffer");
  Image im = Image::make(fb.width(), fb.height(), 1, SampleType::U8);
  const int bits = fb.format().stencil_bits;
  for (std::size_t i = 0; i < im.u8.size(); ++i)
    im.u8[i] = stretch ? static_cast<std::uint8_t>(unorm_convert(fb.stencil()[i], bits, 8)) : fb.stencil()[i];
  return im;
}

Image depth_image(const Framebuffer& fb) {
  if (!fb.has_depth()) throw FramebufferError("the framebuffer has no depth buffer");
  Image im = Image::make(fb.width(), fb.height(), 1, SampleType::U16);
  const int bits = fb.format().depth_bits;
  for (std::size_t i = 0; i < im.u16.size(); ++i)
    im.u16[i] = static_cast<std::uint16_t>(unorm_convert(fb.depth()[i], bits, 16));
  return im;
}

}  // namespace ffsim
