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
      default: {  // an upload (most steps): two in three repeat the previous call (the
                  // cache stores a call seen twice, so the third hits)
        if (uploads == 0 || pick(3) == 0)
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

TEST_CASE("upload cache: the same upload hits from its third time, any changed input misses") {
  Context ctx(profile("geforce256"), 4, 4);
  std::vector<std::uint8_t> im(4 * 8 * 8, 100);
  auto upload = [&] { ctx.texImage2D(gl::TEXTURE_2D, 0, gl::RGBA8, 8, 8, 0, gl::RGBA, gl::UNSIGNED_BYTE, im.data()); };
  auto level = [&] { return ctx.bound_texture(0, gl::TEXTURE_2D).levels.at(0).codes; };
  const UploadCache& cache = ctx.upload_cache();
  upload();  // seen once: its hash remembered, nothing stored (admission)
  const auto first = level();
  CHECK(cache.entries() == 0);
  upload();  // seen twice: computed, then stored
  CHECK(cache.hits() == 0);
  CHECK(cache.entries() == 1);
  upload();
  CHECK(cache.hits() == 1);
  CHECK(level() == first);
  // Each of these changes the result; each must miss (and the level follows it).
  ctx.pixelTransferf(gl::RED_BIAS, 0.25);
  upload();
  CHECK(cache.hits() == 1);
  CHECK(level()[0] == 164);  // 100/255 + 0.25 = 0.642 -> round(0.642 * 255) = 164
  ctx.pixelTransferf(gl::RED_BIAS, 0);
  upload();  // back to the first state: a hit, the first level
  CHECK(cache.hits() == 2);
  CHECK(level() == first);
  im[0] = 101;  // the client bytes
  upload();
  CHECK(cache.hits() == 2);
  CHECK(level()[0] == 101);
  ctx.texImage2D(gl::TEXTURE_2D, 0, gl::RGB8, 8, 8, 0, gl::RGBA, gl::UNSIGNED_BYTE, im.data());  // internal format
  CHECK(cache.hits() == 2);
  CHECK(ctx.bound_texture(0, gl::TEXTURE_2D).levels.at(0).base == BaseFormat::RGB);
  // Bytes outside the image the unpack reads (beyond its extent) do not matter:
  // this call is the RGB8 call's second sighting (stored), the next one hits.
  std::vector<std::uint8_t> longer(im);
  longer.resize(im.size() + 64, 7);
  const std::size_t stored = cache.entries();
  ctx.texImage2D(gl::TEXTURE_2D, 0, gl::RGB8, 8, 8, 0, gl::RGBA, gl::UNSIGNED_BYTE, longer.data());
  CHECK(cache.entries() == stored + 1);
  ctx.texImage2D(gl::TEXTURE_2D, 0, gl::RGB8, 8, 8, 0, gl::RGBA, gl::UNSIGNED_BYTE, im.data());
  CHECK(cache.hits() == 3);
}

namespace {
TextureImage texels(std::size_t n) {
  TextureImage im;
  im.codes.assign(n, 1);
  return im;
}
// Offered twice: stored (admission).
void store(UploadCache& cache, const UploadKey& k, const TextureImage& im) {
  cache.insert(k, im);
  cache.insert(k, im);
}
}  // namespace

TEST_CASE("upload cache: entries beyond the byte budget are evicted oldest first") {
  UploadCache cache(1000);
  const TextureImage im = texels(200);  // 400 bytes of texels
  const UploadKey a = UploadKey::make("a", ""), b = UploadKey::make("b", ""), c = UploadKey::make("c", "");
  store(cache, a, im);
  store(cache, b, im);
  CHECK(cache.entries() == 2);
  CHECK(cache.bytes() == 802);
  store(cache, c, im);  // over the budget: "a" goes
  CHECK(cache.entries() == 2);
  CHECK(cache.find(a) == nullptr);
  CHECK(cache.find(b) != nullptr);
  CHECK(cache.find(c) != nullptr);
  const UploadKey d = UploadKey::make("d", "");
  store(cache, d, texels(600));  // larger than the whole budget: not stored, nothing evicted
  CHECK(cache.find(d) == nullptr);
  CHECK(cache.entries() == 2);
  CHECK(cache.bytes() <= 1000);
  cache.clear();
  CHECK(cache.entries() == 0);
  CHECK(cache.bytes() == 0);
  cache.insert(b, im);  // clear() forgets the hashes seen too: a first offer again
  CHECK(cache.entries() == 0);
}

TEST_CASE("upload cache: a hit needs every input byte equal, whatever the hash") {
  UploadCache cache;
  const TextureImage im = texels(4);
  const std::string data = "client bytes", other = "client bytez";
  const UploadKey k = UploadKey::make("head", data);
  store(cache, k, im);
  REQUIRE(cache.find(k) != nullptr);
  // The same hash (forced) with different bytes in the data, or in the head: no hit.
  UploadKey data_differs = UploadKey::make("head", other);
  data_differs.hash = k.hash;
  CHECK(cache.find(data_differs) == nullptr);
  UploadKey head_differs = UploadKey::make("hexd", data);
  head_differs.hash = k.hash;
  CHECK(cache.find(head_differs) == nullptr);
  // Both stored under the one hash, each found as itself.
  store(cache, data_differs, texels(8));
  CHECK(cache.entries() == 2);
  CHECK(cache.find(k)->codes.size() == 4);
  CHECK(cache.find(data_differs)->codes.size() == 8);
  // The split between head and data is part of the inputs: ("ab", "c") is not ("a", "bc").
  UploadKey split = UploadKey::make("hea", "d" + data);
  split.hash = k.hash;
  CHECK(cache.find(split) == nullptr);
}

TEST_CASE("upload cache: the hashes seen once are bounded") {
  UploadCache cache;
  const TextureImage im = texels(1);
  for (std::size_t i = 0; i < UploadCache::kSeenLimit; ++i) cache.insert(UploadKey::make(std::to_string(i), ""), im);
  CHECK(cache.entries() == 0);
  cache.insert(UploadKey::make("0", ""), im);  // still remembered: stored
  CHECK(cache.entries() == 1);
  cache.insert(UploadKey::make("new", ""), im);   // remembered: the limit reached again
  cache.insert(UploadKey::make("new2", ""), im);  // beyond it: all forgotten, then "new2" remembered
  cache.insert(UploadKey::make("1", ""), im);     // forgotten: a first offer again
  CHECK(cache.entries() == 1);
  cache.insert(UploadKey::make("new2", ""), im);
  CHECK(cache.entries() == 2);
}
