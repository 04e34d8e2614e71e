// glTexImage1D/2D, glTexSubImage1D/2D, glCopyTexImage1D/2D, glCopyTexSubImage1D/2D
// (GL121 §3.8.1-3.8.2): client data or framebuffer pixels through the transfer
// plan, then conversion to the internal format (§3.8.1, Table 3.15) into the
// TextureImage levels of the bound texture object.
#include <algorithm>
#include <optional>

#include "pipeline/gl/enum_names.h"
#include "pipeline/pixel_transfer/byte_texels.h"
#include "pipeline/pixel_transfer/final_conversion.h"
#include "pipeline/pixel_transfer/formats.h"
#include "pipeline/pixel_transfer/unpack.h"
#include "sim/context.h"
#include "sim/worker_pool.h"

namespace ffsim {

using pixel::RgbaImage;

namespace {
constexpr int kMaxLevel = 11;  // log2(kMaxTextureSize)
// w = 2^k + 2*border for some k >= 0 (GL121 §3.8.1), or 0.
bool valid_texture_side(int w, int border) {
  if (w == 0) return true;
  const int s = w - 2 * border;
  return s >= 1 && s <= pixel::kMaxTextureSize && (s & (s - 1)) == 0;
}
bool check_client_format(Context& ctx, const char* fn, GLenum format, GLenum type) {
  if (pixel::color_format_components(format) == 0)
    return ctx.error(gl::INVALID_ENUM, fn, gl::enum_name(format) + " is not a colour format of texture data");
  if (pixel::type_size(type) == 0) {
    if (pixel::is_unsupported_gl_type(type))
      return ctx.error(gl::INVALID_ENUM, fn, gl::enum_name(type) + " (packed or bitmap) is not supported by ffsim");
    return ctx.error(gl::INVALID_ENUM, fn, gl::enum_name(type) + " is not a pixel type");
  }
  return true;
}
}  // namespace

// One-byte client data through a component-wise transfer plan (fixed profiles,
// the fast paths): the tables that give the codes of a level shaped like `shape`
// (pipeline/pixel_transfer/byte_texels.h; the same bits as unpack, transfer and
// store_texels). Nothing when the path does not apply.
template <class T>
std::optional<pixel::ByteTexelTables> Context::byte_texel_tables(int dims, GLenum format, GLenum type,
                                                                 const TextureImage& shape) const {
  if (!fast_paths_ || !profile_.is_fixed() || (type != gl::UNSIGNED_BYTE && type != gl::BYTE)) return std::nullopt;
  const pixel::TransferInputs in = transfer_inputs();
  const pixel::TransferPlan plan =
      pixel::plan_transfer(in, dims == 1 ? pixel::ImageDims::OneD : pixel::ImageDims::TwoD);
  if (!pixel::plan_is_componentwise(plan)) return std::nullopt;
  return pixel::byte_texel_tables<T>(format, type, plan, in, shape, profile_);
}

template <class T>
bool Context::upload_in_bands(const void* data, int width, int height, GLenum format, GLenum type,
                              pixel::ImageDims dims, int x0, int y0, const std::function<TextureImage&()>& target) {
  if (threads_ <= 1 || !data || height < 2 || static_cast<std::int64_t>(width) * height < kSplitUploadTexels)
    return false;
  const pixel::TransferInputs in = transfer_inputs();
  const pixel::TransferPlan plan = pixel::plan_transfer(in, dims);
  if (plan.has(pixel::Stage::Convolution)) return false;  // a pixel's result reads its neighbours
  TextureImage& ti = target();
  const int bands = std::min(height, 2 * threads_);
  ++split_uploads_;
  // Each pixel through the same unpack, plan and store_texels as the whole image
  // (make_texture_image is texture_level + store_texels at (0, 0)); the bands'
  // rows are disjoint. Band k's first row r0 is read as if UNPACK_SKIP_ROWS were
  // r0 larger (ClientLayout::offset: the skip and the row add alike).
  run_split(bands, [&](int k) {
    const int r0 = static_cast<int>(static_cast<std::int64_t>(height) * k / bands);
    const int r1 = static_cast<int>(static_cast<std::int64_t>(height) * (k + 1) / bands);
    pixel::PixelStoreModes u = pixel_store_.unpack;
    u.skip_rows += r0;
    RgbaImage<T> rows = pixel::unpack_rgba<T>(data, width, r1 - r0, format, type, u);
    rows = pixel::run_plan(plan, in, std::move(rows));
    pixel::store_texels(rows, ti, x0, y0 + r0, profile_);
  });
  return true;
}

template <class T>
bool Context::tex_image(const char* fn, int dims, GLenum target, int level, GLenum internalformat, int width,
                        int height, int border, GLenum format, GLenum type, const void* data, const int* copy_xy) {
  const GLenum want = dims == 1 ? gl::TEXTURE_1D : gl::TEXTURE_2D;
  if (target != want) return error(gl::INVALID_ENUM, fn, "target must be " + gl::enum_name(want) + " (got " +
                                                             gl::enum_name(target) + ")");
  if (level < 0 || level > kMaxLevel)
    return error(gl::INVALID_VALUE, fn, "level must be 0.." + std::to_string(kMaxLevel) + " (got " +
                                            std::to_string(level) + ")");
  const auto f = pixel::texture_internal_format(internalformat);
  if (!f) return error(gl::INVALID_VALUE, fn, gl::enum_name(internalformat) + " is not a texture internal format");
  if (border != 0 && border != 1)
    return error(gl::INVALID_VALUE, fn, "border must be 0 or 1 (got " + std::to_string(border) + ")");
  if (width < 0 || height < 0)
    return error(gl::INVALID_VALUE, fn, "width and height must not be negative");
  if (!copy_xy && !check_client_format(*this, fn, format, type)) return false;
  const pixel::ImageDims idims = dims == 1 ? pixel::ImageDims::OneD : pixel::ImageDims::TwoD;
  int ow = 0, oh = 0;
  pixel::transfer_output_size(transfer_inputs(), idims, width, height, ow, oh);
  if (dims == 1) oh = 1;
  if (!valid_texture_side(ow, border) || (dims == 2 && !valid_texture_side(oh, border)))
    return error(gl::INVALID_VALUE, fn, "image size " + std::to_string(ow) + "x" + std::to_string(oh) +
                                            " (after convolution) is not 2^k + 2*border with 2^k <= " +
                                            std::to_string(pixel::kMaxTextureSize));
  TextureObject& obj = bound_texture(active_unit_, target);
  auto level_image = [&]() -> TextureImage& {
    if (static_cast<int>(obj.levels.size()) <= level) obj.levels.resize(static_cast<std::size_t>(level) + 1);
    obj.target = target;
    ++obj.version;
    return obj.levels[static_cast<std::size_t>(level)];
  };
  // Client data with the fast paths: the upload cache (sim/upload_cache.h) keyed
  // by every input of the result (the profile is the context's, fixed).
  std::optional<UploadKey> key;
  if (fast_paths_ && data && !copy_xy && ow > 0 && oh > 0) {
    const pixel::ClientLayout layout = pixel::client_layout(pixel_store_.unpack, width, height,
                                                            pixel::color_format_components(format), pixel::type_size(type));
    std::string head;
    head.reserve(4096);
    for (const int v : {dims, width, height, border, static_cast<int>(sizeof(T))}) append_bytes(head, v);
    for (const GLenum e : {internalformat, format, type}) append_bytes(head, e);
    append_transfer_key(head, pixel_store_.unpack, transfer_inputs());
    key = UploadKey::make(std::move(head), {static_cast<const char*>(data), layout.extent(width, height)});
    if (const TextureImage* hit = upload_cache_.find(*key)) {
      level_image() = *hit;
      return true;
    }
  }
  if (data && !copy_xy && ow > 0 && oh > 0) {
    TextureImage shape = pixel::texture_level(0, 0, internalformat, *f, border, profile_);
    if (const auto tab = byte_texel_tables<T>(dims, format, type, shape)) {
      TextureImage& ti = level_image();
      ti = pixel::texture_level(ow, oh, internalformat, *f, border, profile_);
      pixel::store_byte_texels(*tab, data, width, height, pixel_store_.unpack, ti, 0, 0);
      if (key) upload_cache_.insert(*key, ti);
      return true;
    }
  }
  if (data && !copy_xy && ow > 0 && oh > 0 &&
      upload_in_bands<T>(data, width, height, format, type, idims, 0, 0, [&]() -> TextureImage& {
        TextureImage& ti = level_image();
        ti = pixel::texture_level(ow, oh, internalformat, *f, border, profile_);
        return ti;
      })) {
    if (key) upload_cache_.insert(*key, obj.levels[static_cast<std::size_t>(level)]);
    return true;
  }
  RgbaImage<T> img;
  if (copy_xy) img = read_color_rect<T>(copy_xy[0], copy_xy[1], width, height);
  else if (data) img = pixel::unpack_rgba<T>(data, width, height, format, type, pixel_store_.unpack);
  if (copy_xy || data) img = transfer(std::move(img), idims);
  else img = RgbaImage<T>(ow, oh);  // no data: contents undefined (GL121 §3.8.1); ffsim stores 0
  if (ow == 0 || oh == 0) img = RgbaImage<T>(0, 0);
  TextureImage& ti = level_image();
  ti = pixel::make_texture_image(img, internalformat, *f, border, profile_);
  if (key) upload_cache_.insert(*key, ti);
  return true;
}

template <class T>
bool Context::tex_sub_image(const char* fn, int dims, GLenum target, int level, int xoffset, int yoffset, int width,
                            int height, GLenum format, GLenum type, const void* data, const int* copy_xy) {
  const GLenum want = dims == 1 ? gl::TEXTURE_1D : gl::TEXTURE_2D;
  if (target != want) return error(gl::INVALID_ENUM, fn, "target must be " + gl::enum_name(want) + " (got " +
                                                             gl::enum_name(target) + ")");
  if (level < 0 || level > kMaxLevel)
    return error(gl::INVALID_VALUE, fn, "level must be 0.." + std::to_string(kMaxLevel));
  if (width < 0 || height < 0) return error(gl::INVALID_VALUE, fn, "width and height must not be negative");
  if (!copy_xy && !check_client_format(*this, fn, format, type)) return false;
  TextureObject& obj = bound_texture(active_unit_, target);
  if (static_cast<int>(obj.levels.size()) <= level || obj.levels[level].empty())
    return error(gl::INVALID_OPERATION, fn, "level " + std::to_string(level) + " has not been specified");
  TextureImage& ti = obj.levels[level];
  const pixel::ImageDims idims = dims == 1 ? pixel::ImageDims::OneD : pixel::ImageDims::TwoD;
  int ow = 0, oh = 0;
  pixel::transfer_output_size(transfer_inputs(), idims, width, height, ow, oh);
  if (dims == 1) oh = 1;
  const int b = ti.border;
  // §3.8.2: -b <= xoffset, xoffset + w <= w_t - b (and likewise in y for 2D).
  if (xoffset < -b || xoffset + ow > ti.width - b || (dims == 2 && (yoffset < -b || yoffset + oh > ti.height - b)))
    return error(gl::INVALID_VALUE, fn, "the region " + std::to_string(ow) + "x" + std::to_string(oh) + " at (" +
                                            std::to_string(xoffset) + ", " + std::to_string(yoffset) +
                                            ") is outside the level");
  if (!copy_xy && !data && ow > 0 && oh > 0) return error(gl::INVALID_VALUE, fn, "no image data");
  if (!copy_xy && ow > 0 && oh > 0)
    if (const auto tab = byte_texel_tables<T>(dims, format, type, ti)) {
      pixel::store_byte_texels(*tab, data, width, height, pixel_store_.unpack, ti, xoffset + b,
                               dims == 1 ? 0 : yoffset + b);
      ++obj.version;
      return true;
    }
  if (!copy_xy && ow > 0 && oh > 0 &&
      upload_in_bands<T>(data, width, height, format, type, idims, xoffset + b, dims == 1 ? 0 : yoffset + b,
                         [&]() -> TextureImage& { return ti; })) {
    ++obj.version;
    return true;
  }
  RgbaImage<T> img = copy_xy ? read_color_rect<T>(copy_xy[0], copy_xy[1], width, height)
                             : pixel::unpack_rgba<T>(data, width, height, format, type, pixel_store_.unpack);
  img = transfer(std::move(img), idims);
  if (img.empty()) return true;
  pixel::store_texels(img, ti, xoffset + b, dims == 1 ? 0 : yoffset + b, profile_);
  ++obj.version;
  return true;
}


void Context::texImage1D(GLenum target, int level, GLenum internalformat, int width, int border, GLenum format,
                         GLenum type, const void* data) {
  if (reject_in_begin("glTexImage1D")) return;
  if (profile_.arithmetic == Arithmetic::Float64)
    tex_image<double>("glTexImage1D", 1, target, level, internalformat, width, 1, border, format, type, data, nullptr);
  else
    tex_image<float>("glTexImage1D", 1, target, level, internalformat, width, 1, border, format, type, data, nullptr);
}

void Context::texImage2D(GLenum target, int level, GLenum internalformat, int width, int height, int border,
                         GLenum format, GLenum type, const void* data) {
  if (reject_in_begin("glTexImage2D")) return;
  if (profile_.arithmetic == Arithmetic::Float64)
    tex_image<double>("glTexImage2D", 2, target, level, internalformat, width, height, border, format, type, data,
                      nullptr);
  else
    tex_image<float>("glTexImage2D", 2, target, level, internalformat, width, height, border, format, type, data,
                     nullptr);
}

void Context::texSubImage1D(GLenum target, int level, int xoffset, int width, GLenum format, GLenum type,
                            const void* data) {
  if (reject_in_begin("glTexSubImage1D")) return;
  if (profile_.arithmetic == Arithmetic::Float64)
    tex_sub_image<double>("glTexSubImage1D", 1, target, level, xoffset, 0, width, 1, format, type, data, nullptr);
  else
    tex_sub_image<float>("glTexSubImage1D", 1, target, level, xoffset, 0, width, 1, format, type, data, nullptr);
}

void Context::texSubImage2D(GLenum target, int level, int xoffset, int yoffset, int width, int height, GLenum format,
                            GLenum type, const void* data) {
  if (reject_in_begin("glTexSubImage2D")) return;
  if (profile_.arithmetic == Arithmetic::Float64)
    tex_sub_image<double>("glTexSubImage2D", 2, target, level, xoffset, yoffset, width, height, format, type, data,
                          nullptr);
  else
    tex_sub_image<float>("glTexSubImage2D", 2, target, level, xoffset, yoffset, width, height, format, type, data,
                         nullptr);
}

void Context::copyTexImage1D(GLenum target, int level, GLenum internalformat, int x, int y, int width, int border) {
  if (reject_in_begin("glCopyTexImage1D")) return;
  const int xy[2] = {x, y};
  if (profile_.arithmetic == Arithmetic::Float64)
    tex_image<double>("glCopyTexImage1D", 1, target, level, internalformat, width, 1, border, 0, 0, nullptr, xy);
  else
    tex_image<float>("glCopyTexImage1D", 1, target, level, internalformat, width, 1, border, 0, 0, nullptr, xy);
}

void Context::copyTexImage2D(GLenum target, int level, GLenum internalformat, int x, int y, int width, int height,
                             int border) {
  if (reject_in_begin("glCopyTexImage2D")) return;
  const int xy[2] = {x, y};
  if (profile_.arithmetic == Arithmetic::Float64)
    tex_image<double>("glCopyTexImage2D", 2, target, level, internalformat, width, height, border, 0, 0, nullptr, xy);
  else
    tex_image<float>("glCopyTexImage2D", 2, target, level, internalformat, width, height, border, 0, 0, nullptr, xy);
}

void Context::copyTexSubImage1D(GLenum target, int level, int xoffset, int x, int y, int width) {
  if (reject_in_begin("glCopyTexSubImage1D")) return;
  const int xy[2] = {x, y};
  if (profile_.arithmetic == Arithmetic::Float64)
    tex_sub_image<double>("glCopyTexSubImage1D", 1, target, level, xoffset, 0, width, 1, 0, 0, nullptr, xy);
  else
    tex_sub_image<float>("glCopyTexSubImage1D", 1, target, level, xoffset, 0, width, 1, 0, 0, nullptr, xy);
}

void Context::copyTexSubImage2D(GLenum target, int level, int xoffset, int yoffset, int x, int y, int width,
                                int height) {
  if (reject_in_begin("glCopyTexSubImage2D")) return;
  const int xy[2] = {x, y};
  if (profile_.arithmetic == Arithmetic::Float64)
    tex_sub_image<double>("glCopyTexSubImage2D", 2, target, level, xoffset, yoffset, width, height, 0, 0, nullptr, xy);
  else
    tex_sub_image<float>("glCopyTexSubImage2D", 2, target, level, xoffset, yoffset, width, height, 0, 0, nullptr, xy);
}

}  // namespace ffsim
