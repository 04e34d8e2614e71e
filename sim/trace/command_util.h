// Helpers shared by the area command files (sim/trace/commands_<area>.cpp):
// client images as GL client memory, and load-time checks of vector arguments.
//
// A client image is the client memory of a call taking pixels: its samples are the
// bytes the GL reads (8-bit codes for UNSIGNED_BYTE/BYTE, 16-bit for
// UNSIGNED_SHORT/SHORT, binary32 for FLOAT), channels = the elements per group of
// `format`. The loader rejects an image whose sample type or channel count does
// not match `format`/`type`; at run time the bytes the GL would read under the
// current UNPACK modes (Context::pixel_client_bytes) must lie inside the image,
// otherwise the replay stops with the call's position (never a read past the data).
#pragma once
#include <array>
#include <cstddef>
#include <initializer_list>
#include <optional>
#include <string>
#include <vector>

#include "pipeline/gl/enum_names.h"
#include "sim/trace/binder.h"
#include "sim/trace/error.h"

namespace ffsim::trace {

// Elements per group of a client pixel format (RED .. BGRA, LUMINANCE(_ALPHA),
// COLOR_INDEX, STENCIL_INDEX, DEPTH_COMPONENT); 0 for other values.
int client_format_channels(GLenum format);
// The client image sample type that holds elements of `type`; nullopt when no
// client image can (INT, UNSIGNED_INT, packed and unknown types).
std::optional<SampleType> client_sample_type(GLenum type);
// "8-bit", "16-bit", "float".
std::string sample_type_name(SampleType t);
// Bytes of an image's sample data.
std::size_t image_bytes(const Image& im);

// Load-time check that the image argument `image` fits the `format` and `type`
// arguments of `fn` (reported at the format, the type or the image).
std::optional<ArgProblem> check_client_image(const std::vector<ArgValue>& a, std::size_t format, std::size_t type,
                                             std::size_t image, const std::string& fn);

// The image's data for a call reading width x height groups of format/type under
// the current UNPACK modes; throws TraceError at the image argument when the GL
// would read past its end.
const void* unpack_source(const Context& c, const Args& a, std::size_t image, int width, int height, GLenum format,
                          GLenum type, const char* fn);

// The zero-filled client image glReadPixels writes for width x height groups of
// format/type (0 x 0 for negative sizes, which the GL rejects).
Image client_image_for(int width, int height, GLenum format, GLenum type);

// Load-time count check of a vector argument whose size depends on pname: 4 values
// for the pnames in `four`, 1 otherwise ("glTexEnvfv GL_TEXTURE_ENV_COLOR takes 4
// values, got 3").
std::optional<ArgProblem> check_vector_count(const std::vector<ArgValue>& a, std::size_t pname, std::size_t values,
                                             const std::vector<GLenum>& four, const std::string& fn);
// Load-time check that every value of a Numbers argument is an integer in [lo, hi].
std::optional<ArgProblem> check_integers(const std::vector<ArgValue>& a, std::size_t values, double lo, double hi,
                                         const std::string& what);
// Up to 4 values, zero-padded (the GL reads 1 or 4 depending on pname).
std::array<double, 4> padded4(const std::vector<double>& v);

}  // namespace ffsim::trace
