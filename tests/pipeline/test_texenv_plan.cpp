// The shading plan (pipeline/texenv/shading.h): skipped units and samples never
// change an output bit. Random unit configurations and fragments run through
// plan_shading and through full_shading_plan; outputs must be identical.
#include <doctest/doctest.h>

#include <random>

#include "pipeline/texenv/shading.h"

using namespace ffsim;

namespace {

TextureObject random_texture(std::mt19937& rng, BaseFormat base) {
  TextureObject t;
  TextureImage im;
  im.width = 4;
  im.height = 4;
  im.base = base;
  im.bits = 8;
  for (int i = 0; i < 16 * component_count(base); ++i) {
    im.codes.push_back(static_cast<std::uint16_t>(rng() % 256));
    im.values.push_back(im.codes.back() / 255.0);
  }
  t.levels.push_back(im);
  t.params.min_filter = t.params.mag_filter = (rng() % 2) ? gl::LINEAR : gl::NEAREST;
  return t;
}

template <class T, std::size_t N>
T pick(std::mt19937& rng, const std::array<T, N>& a) {
  return a[rng() % N];
}

}  // namespace

TEST_CASE("shading plan: planned path equals the full path on random configurations") {
  std::mt19937 rng(12345);
  const std::array<BaseFormat, 6> bases{BaseFormat::Alpha, BaseFormat::Luminance, BaseFormat::LuminanceAlpha,
                                         BaseFormat::Intensity, BaseFormat::RGB, BaseFormat::RGBA};
  const std::array<GLenum, 6> modes{gl::REPLACE, gl::MODULATE, gl::DECAL, gl::BLEND, gl::ADD, gl::COMBINE};
  const std::array<GLenum, 10> frgb{gl::REPLACE, gl::MODULATE, gl::ADD, gl::ADD_SIGNED, gl::INTERPOLATE,
                                    gl::SUBTRACT, gl::DOT3_RGB, gl::DOT3_RGBA, gl::DOT3_RGB_EXT, gl::DOT3_RGBA_EXT};
  const std::array<GLenum, 6> falpha{gl::REPLACE, gl::MODULATE, gl::ADD, gl::ADD_SIGNED, gl::INTERPOLATE, gl::SUBTRACT};
  const std::array<GLenum, 4> srcs{gl::TEXTURE, gl::CONSTANT, gl::PRIMARY_COLOR, gl::PREVIOUS};
  const std::array<GLenum, 4> ops{gl::SRC_COLOR, gl::ONE_MINUS_SRC_COLOR, gl::SRC_ALPHA, gl::ONE_MINUS_SRC_ALPHA};
  const std::array<GLenum, 2> aops{gl::SRC_ALPHA, gl::ONE_MINUS_SRC_ALPHA};
  int skipped_units = 0, skipped_samples = 0;
  for (Arithmetic arith : {Arithmetic::Fixed, Arithmetic::Float64}) {
    for (int trial = 0; trial < 400; ++trial) {
      std::array<TextureObject, kShadeUnits> texs;
      ShadingState st;
      st.color = {arith, 8};
      st.sample = {arith, 8};
      st.color_sum = rng() % 2;
      for (int u = 0; u < kShadeUnits; ++u) {
        texs[u] = random_texture(rng, pick(rng, bases));
        ShadeUnit& su = st.units[u];
        if (rng() % 4 != 0) su.texture = &texs[u];
        TexEnvState& e = su.env;
        e.mode = pick(rng, modes);
        e.color = {(rng() % 256) / 255.0, (rng() % 256) / 255.0, (rng() % 256) / 255.0, (rng() % 256) / 255.0};
        e.combine_rgb = pick(rng, frgb);
        e.combine_alpha = pick(rng, falpha);
        for (int i = 0; i < 3; ++i) {
          e.source_rgb[i] = pick(rng, srcs);
          e.source_alpha[i] = pick(rng, srcs);
          e.operand_rgb[i] = pick(rng, ops);
          e.operand_alpha[i] = pick(rng, aops);
        }
        e.rgb_scale = 1 << (rng() % 3);
        e.alpha_scale = 1 << (rng() % 3);
      }
      const ShadingPlan plan = plan_shading(st), full = full_shading_plan(st);
      for (int u = 0; u < kShadeUnits; ++u) {
        skipped_units += full.env[u] && !plan.env[u];
        skipped_samples += full.sample[u] && !plan.sample[u];
      }
      for (int f = 0; f < 8; ++f) {
        Rgba prim, sec;
        for (int c = 0; c < 4; ++c) {
          prim.code[c] = rng() % 256;
          sec.code[c] = rng() % 256;
          prim.value[c] = prim.code[c] / 255.0;
          sec.value[c] = sec.code[c] / 255.0;
        }
        UnitTexCoords tc{};
        for (auto& t : tc) t = {(rng() % 1000) / 250.0 - 2, (rng() % 1000) / 250.0 - 2, 0};
        UnitTexels a{}, b{};
        // Stale texels in the planned path's unsampled slots must not matter.
        for (auto& t : a)
          for (auto& k : t.code) k = static_cast<std::uint32_t>(rng() % 256);
        fetch_texels(st, plan, tc, a);
        fetch_texels(st, full, tc, b);
        const Rgba pa = texture_environments(st, plan, prim, sec, a);
        const Rgba pb = texture_environments(st, full, prim, sec, b);
        REQUIRE_MESSAGE(pa == pb, "trial " << trial << "\n" << explain_shading(st, plan));
      }
    }
  }
  // The test exercises skipping, not just the trivial plan.
  CHECK(skipped_units > 50);
  CHECK(skipped_samples > 50);
}

TEST_CASE("shading plan: a later REPLACE of an RGBA texture makes earlier units unread") {
  TextureObject t;
  TextureImage im;
  im.width = im.height = 1;
  im.base = BaseFormat::RGBA;
  im.codes = {1, 2, 3, 4};
  t.levels.push_back(im);
  ShadingState st;
  st.units[0].texture = &t;
  st.units[1].texture = &t;
  st.units[1].env.mode = gl::REPLACE;
  ShadingPlan p = plan_shading(st);
  CHECK_FALSE(p.env[0]);
  CHECK_FALSE(p.sample[0]);
  CHECK(p.env[1]);
  CHECK(explain_shading(st, p).find("texture unit 0: skipped") != std::string::npos);
  // A COMBINE that reads only PRIMARY_COLOR and CONSTANT runs but samples nothing.
  st.units[1].env.mode = gl::COMBINE;
  st.units[1].env.combine_rgb = gl::MODULATE;
  st.units[1].env.combine_alpha = gl::REPLACE;
  st.units[1].env.source_rgb = {gl::PRIMARY_COLOR, gl::CONSTANT, gl::TEXTURE};
  st.units[1].env.source_alpha = {gl::CONSTANT, gl::TEXTURE, gl::TEXTURE};
  p = plan_shading(st);
  CHECK(p.env[1]);
  CHECK_FALSE(p.sample[1]);
  CHECK_FALSE(p.env[0]);
}
