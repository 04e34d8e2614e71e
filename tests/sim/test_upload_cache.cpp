// The texture-upload cache (sim/upload_cache.h): a cached context and a context
// without fast paths (every upload computed) take the same random sequence of
// pixel-state changes and glTexImage1D/2D calls; every upload must store the same
// level bit for bit, whether the cache hit or not. The sequence re-uploads
// earlier images often (hits) and changes one input at a time (which must miss).
// Misses and sub-images of one-byte data take the table path of
// pipeline/pixel_transfer/byte_texels.h when the transfer is component-wise.
#include <doctest/doctest.h>

#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "sim/context.h"

using namespace ffsim;

namespace {

Profile profile(const std::string& name) { return *find_builtin_profile(name); }

struct Pair {
  Context cached, reference;
  Pair(const Profile& p) : cached(p, 4, 4), reference(p, 4, 4) { reference.set_fast_paths(false); }
  template <class F>
  void both(F f) {
    f(cached);
    f(reference);
  }
};

void check_same_level(Context& a, Context& b, GLenum target, int level) {
  CHECK(a.getError() == b.getError());
  const TextureObject& ta = a.bound_texture(0, target);
  const TextureObject& tb = b.bound_texture(0, target);
  REQUIRE(ta.levels.size() == tb.levels.size());
  if (ta.levels.size() <= static_cast<std::size_t>(level)) return;
  const TextureImage& x = ta.levels[static_cast<std::size_t>(level)];
  const TextureImage& y = tb.levels[static_cast<std::size_t>(level)];
  CHECK(x.width == y.width);
  CHECK(x.height == y.height);
  CHECK(x.border == y.border);
  CHECK(x.internal_format == y.internal_format);
  CHECK(x.base == y.base);
  CHECK(x.bits == y.bits);
  CHECK(x.codes == y.codes);
  CHECK(x.values == y.values);
  CHECK(ta.version == tb.version);
}

void random_sequence(const std::string& profile_name, std::uint32_t seed, int steps) {
  CAPTURE(profile_name);
  CAPTURE(seed);
  std::mt19937 rng(seed);
  auto pick = [&](int n) { return static_cast<int>(rng() % static_cast<std::uint32_t>(n)); };
  auto unit = [&] { return static_cast<double>(rng() % 1001) / 1000.0; };
  Pair p(profile(profile_name));
  // A few client images (bytes), re-used often; 16 x 16 RGBA8 plus slack for the unpack modes.
  std::vector<std::vector<std::uint8_t>> images(3, std::vector<std::uint8_t>(4 * 20 * 20));
  for (auto& im : images)
    for (auto& b : im) b = static_cast<std::uint8_t>(rng());
  const GLenum formats[] = {gl::RGBA, gl::RGB, gl::LUMINANCE, gl::ALPHA};
  const GLenum internals[] = {gl::RGBA8, gl::RGB8, gl::ALPHA8, gl::LUMINANCE, gl::RGBA4, gl::INTENSITY};
  int uploads = 0;
  struct Call {
    int image;
    GLenum format, internal;
    int level;
    bool one_d;
    GLenum type;
  } call{};
  for (int step = 0; step < steps; ++step) {
    CAPTURE(step);
    switch (pick(9)) {
      case 0: {  // scale or bias of one component
        const GLenum names[] = {gl::RED_SCALE, gl::GREEN_BIAS, gl::ALPHA_SCALE, gl::POST_COLOR_MATRIX_ALPHA_BIAS,
                                gl::POST_COLOR_MATRIX_RED_SCALE};
        const GLenum n = names[pick(5)];
        const double v = unit() * 2 - 0.5;
        p.both([&](Context& c) { c.pixelTransferf(n, v); });
        break;
      }
      case 1: {  // the colour matrix
        double m[16];
        for (double& x : m) x = unit() - 0.25;
        p.both([&](Context& c) {
          c.matrixMode(gl::COLOR);
          c.loadMatrix(m);
          c.matrixMode(gl::MODELVIEW);
        });
        break;
      }
      case 2: {  // a post-colour-matrix table, enabled or not
        std::vector<float> t(4 * 12);  // 8 entries, plus slack for the unpack modes (they apply here too)
        for (float& x : t) x = static_cast<float>(unit());
        const bool on = pick(2) == 0;
        p.both([&](Context& c) {
          c.colorTable(gl::POST_COLOR_MATRIX_COLOR_TABLE, gl::RGBA, 8, gl::RGBA, gl::FLOAT, t.data());
          if (on) c.enable(gl::POST_COLOR_MATRIX_COLOR_TABLE);
          else c.disable(gl::POST_COLOR_MATRIX_COLOR_TABLE);
        });
        break;
      }
      case 3: {  // unpack modes
        const int align = 1 << pick(4), skip = pick(2);
        p.both([&](Context& c) {
          c.pixelStorei(gl::UNPACK_ALIGNMENT, align);
          c.pixelStorei(gl::UNPACK_SKIP_PIXELS, skip);
        });
        break;
      }
      case 4:  // one byte of one client image
        images[static_cast<std::size_t>(pick(3))][static_cast<std::size_t>(pick(4 * 20 * 20))] ^= 0x10;
        break;
      case 5: {  // a colour map with MAP_COLOR
        std::vector<double> m(4);
        for (double& x : m) x = unit();
        const bool on = pick(2) == 0;
        p.both([&](Context& c) {
          c.pixelMapfv(gl::PIXEL_MAP_G_TO_G, 4, m.data());
          c.pixelTransferf(gl::MAP_COLOR, on ? 1.0 : 0.0);
        });
        break;
      }
      default: {  // an upload (most steps): half of them repeat the previous call
        if (uploads == 0 || pick(2) == 0)
          call = {pick(3), formats[pick(4)], internals[pick(6)], pick(2), pick(4) == 0,
                  pick(3) == 0 ? gl::BYTE : gl::UNSIGNED_BYTE};
        const auto& im = images[static_cast<std::size_t>(call.image)];
        const GLenum fmt = call.format, internal = call.internal;
        const int level = call.level, side = level == 0 ? 16 : 8;
        const bool one_d = call.one_d;
        if (one_d) {
          p.both([&](Context& c) { c.texImage1D(gl::TEXTURE_1D, level, internal, side, 0, fmt, call.type, im.data()); });
          check_same_level(p.cached, p.reference, gl::TEXTURE_1D, level);
        } else {
          p.both([&](Context& c) {
            c.texImage2D(gl::TEXTURE_2D, level, internal, side, side, 0, fmt, call.type, im.data());
          });
          check_same_level(p.cached, p.reference, gl::TEXTURE_2D, level);
          if (pick(2) == 0) {  // a sub-image (not cached; one-byte data by table with the fast paths)
            const int x = pick(side), y = pick(side), w = 1 + pick(side - x), h = 1 + pick(side - y);
            const auto& sub = images[static_cast<std::size_t>(pick(3))];
            const GLenum sub_fmt = formats[pick(4)], sub_type = pick(2) ? gl::BYTE : gl::UNSIGNED_BYTE;
            p.both([&](Context& c) { c.texSubImage2D(gl::TEXTURE_2D, level, x, y, w, h, sub_fmt, sub_type, sub.data()); });
            check_same_level(p.cached, p.reference, gl::TEXTURE_2D, level);
          }
        }
        ++uploads;
        break;
      }
    }
  }
  // The sequence exercised both sides of the cache; the reference never used it.
  CHECK(p.cached.upload_cache().hits() > 0);
  CHECK(p.cached.upload_cache().misses() > 0);
  CHECK(p.cached.upload_cache().hits() + p.cached.upload_cache().misses() == static_cast<std::uint64_t>(uploads));
  CHECK(p.reference.upload_cache().hits() + p.reference.upload_cache().misses() == 0);
}

}  // namespace

TEST_CASE("upload cache: random state changes and uploads equal the computed uploads") {
  for (std::uint32_t seed = 1; seed <= 12; ++seed) random_sequence("geforce256", seed, 300);
  for (std::uint32_t seed = 100; seed <= 103; ++seed) random_sequence("rgba12", seed, 200);
  for (std::uint32_t seed = 200; seed <= 201; ++seed) random_sequence("float32", seed, 150);
}

TEST_CASE("upload cache: the same upload hits; any changed input misses") {
  Context ctx(profile("geforce256"), 4, 4);
  std::vector<std::uint8_t> im(4 * 8 * 8, 100);
  auto upload = [&] { ctx.texImage2D(gl::TEXTURE_2D, 0, gl::RGBA8, 8, 8, 0, gl::RGBA, gl::UNSIGNED_BYTE, im.data()); };
  auto level = [&] { return ctx.bound_texture(0, gl::TEXTURE_2D).levels.at(0).codes; };
  upload();
  const auto first = level();
  upload();
  CHECK(ctx.upload_cache().hits() == 1);
  CHECK(level() == first);
  // Each of these changes the result; each must miss (and the level follows it).
  ctx.pixelTransferf(gl::RED_BIAS, 0.25);
  upload();
  CHECK(ctx.upload_cache().hits() == 1);
  CHECK(level()[0] == 164);  // 100/255 + 0.25 = 0.642 -> round(0.642 * 255) = 164
  ctx.pixelTransferf(gl::RED_BIAS, 0);
  upload();  // back to the first state: a hit, the first level
  CHECK(ctx.upload_cache().hits() == 2);
  CHECK(level() == first);
  im[0] = 101;  // the client bytes
  upload();
  CHECK(ctx.upload_cache().hits() == 2);
  CHECK(level()[0] == 101);
  ctx.texImage2D(gl::TEXTURE_2D, 0, gl::RGB8, 8, 8, 0, gl::RGBA, gl::UNSIGNED_BYTE, im.data());  // internal format
  CHECK(ctx.upload_cache().hits() == 2);
  CHECK(ctx.bound_texture(0, gl::TEXTURE_2D).levels.at(0).base == BaseFormat::RGB);
  // Bytes outside the image the unpack reads (beyond its extent) do not matter.
  std::vector<std::uint8_t> longer(im);
  longer.resize(im.size() + 64, 7);
  ctx.texImage2D(gl::TEXTURE_2D, 0, gl::RGB8, 8, 8, 0, gl::RGBA, gl::UNSIGNED_BYTE, longer.data());
  CHECK(ctx.upload_cache().hits() == 3);
}

TEST_CASE("upload cache: entries beyond the byte budget are evicted oldest first") {
  UploadCache cache(1000);
  TextureImage im;
  im.codes.assign(200, 1);  // 400 bytes of texels
  cache.insert("a", im);
  cache.insert("b", im);
  CHECK(cache.entries() == 2);
  CHECK(cache.bytes() == 802);
  cache.insert("c", im);  // over the budget: "a" goes
  CHECK(cache.entries() == 2);
  CHECK(cache.find("a") == nullptr);
  CHECK(cache.find("b") != nullptr);
  CHECK(cache.find("c") != nullptr);
  TextureImage huge;
  huge.codes.assign(600, 1);  // larger than the whole budget: not stored, nothing evicted
  cache.insert("d", huge);
  CHECK(cache.find("d") == nullptr);
  CHECK(cache.entries() == 2);
  CHECK(cache.bytes() <= 1000);
  cache.clear();
  CHECK(cache.entries() == 0);
  CHECK(cache.bytes() == 0);
}
