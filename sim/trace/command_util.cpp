#include "sim/trace/command_util.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "pipeline/gl/enum_names.h"
#include "pipeline/pixel_transfer/formats.h"
#include "sim/trace/expr.h"

namespace ffsim::trace {

int client_format_channels(GLenum format) {
  if (format == gl::COLOR_INDEX || format == gl::STENCIL_INDEX || format == gl::DEPTH_COMPONENT) return 1;
  return pixel::color_format_components(format);
}

std::optional<SampleType> client_sample_type(GLenum type) {
  switch (type) {
    case gl::UNSIGNED_BYTE:
    case gl::BYTE: return SampleType::U8;
    case gl::UNSIGNED_SHORT:
    case gl::SHORT: return SampleType::U16;
    case gl::FLOAT: return SampleType::F32;
    default: return std::nullopt;
  }
}

std::string sample_type_name(SampleType t) {
  switch (t) {
    case SampleType::U8: return "8-bit";
    case SampleType::U16: return "16-bit";
    case SampleType::F32: return "float";
  }
  return "float";
}

std::size_t image_bytes(const Image& im) {
  switch (im.type) {
    case SampleType::U8: return im.u8.size();
    case SampleType::U16: return im.u16.size() * 2;
    case SampleType::F32: return im.f32.size() * 4;
  }
  return 0;
}

namespace {
const void* image_data(const Image& im) {
  switch (im.type) {
    case SampleType::U8: return im.u8.data();
    case SampleType::U16: return im.u16.data();
    case SampleType::F32: return im.f32.data();
  }
  return nullptr;
}
std::string token(const ArgValue& v) { return gl::enum_name(static_cast<GLenum>(v.i)); }
}  // namespace

std::optional<ArgProblem> check_client_image(const std::vector<ArgValue>& a, std::size_t format, std::size_t type,
                                             std::size_t image, const std::string& fn) {
  const GLenum f = static_cast<GLenum>(a.at(format).i);
  const GLenum t = static_cast<GLenum>(a.at(type).i);
  const int channels = client_format_channels(f);
  if (channels == 0)
    return ArgProblem{format, cat(token(a[format]), " is not a pixel format of client images (", fn,
                                  " takes RED, GREEN, BLUE, ALPHA, RGB, RGBA, BGR, BGRA, LUMINANCE, LUMINANCE_ALPHA,"
                                  " COLOR_INDEX, STENCIL_INDEX or DEPTH_COMPONENT data)")};
  const auto st = client_sample_type(t);
  if (!st)
    return ArgProblem{type, cat(token(a[type]), " has no client image form (client images hold 8-bit, 16-bit or float"
                                                " samples: UNSIGNED_BYTE, BYTE, UNSIGNED_SHORT, SHORT or FLOAT)")};
  const Image& im = *a.at(image).image;
  if (im.type != *st || im.channels != channels)
    return ArgProblem{image, cat("image `", a[image].text, "` has ", sample_type_name(im.type), " samples and ",
                                 std::to_string(im.channels), " channel", im.channels == 1 ? "" : "s", "; ", fn, " with ",
                                 token(a[format]), " ", token(a[type]), " reads ", sample_type_name(*st), " samples and ",
                                 std::to_string(channels), " channel", channels == 1 ? "" : "s")};
  return std::nullopt;
}

const void* unpack_source(const Context& c, const Args& a, std::size_t image, int width, int height, GLenum format,
                          GLenum type, const char* fn) {
  const Image& im = a.image_at(image);
  const std::size_t need = c.pixel_client_bytes(false, width, height, format, type);
  const std::size_t have = image_bytes(im);
  if (need > have)
    throw TraceError(a.where_at(image),
                     cat(fn, " reads ", std::to_string(need), " bytes of image `", a[image].text, "` under the current unpack modes,"
                         " but it holds ", std::to_string(have), " (", std::to_string(im.width), "x", std::to_string(im.height),
                         " with tightly packed rows; GL_UNPACK_ALIGNMENT 1 reads such rows)"));
  return image_data(im);
}

Image client_image_for(int width, int height, GLenum format, GLenum type) {
  const int channels = std::max(1, client_format_channels(format));
  const SampleType st = client_sample_type(type).value_or(SampleType::U8);
  if (width <= 0 || height <= 0) return Image::make(0, 0, channels, st);
  return Image::make(width, height, channels, st);
}

std::optional<ArgProblem> check_vector_count(const std::vector<ArgValue>& a, std::size_t pname, std::size_t values,
                                             const std::vector<GLenum>& four, const std::string& fn) {
  const GLenum p = static_cast<GLenum>(a.at(pname).i);
  const std::size_t want = std::find(four.begin(), four.end(), p) != four.end() ? 4 : 1;
  const std::size_t got = a.at(values).list.size();
  if (got == want) return std::nullopt;
  return ArgProblem{values, cat(fn, " ", token(a[pname]), " takes ", std::to_string(want), " value", want == 1 ? "" : "s",
                                ", got ", std::to_string(got))};
}

std::optional<ArgProblem> check_integers(const std::vector<ArgValue>& a, std::size_t values, double lo, double hi,
                                         const std::string& what) {
  for (double v : a.at(values).list)
    if (v != std::floor(v) || v < lo || v > hi)
      return ArgProblem{values, cat(what, " must be integers in [", format_number(lo), ", ", format_number(hi), "], got ",
                                    format_number(v))};
  return std::nullopt;
}

std::array<double, 4> padded4(const std::vector<double>& v) {
  std::array<double, 4> r{0, 0, 0, 0};
  for (std::size_t k = 0; k < v.size() && k < 4; ++k) r[k] = v[k];
  return r;
}

}  // namespace ffsim::trace
