// The combiner plan: skipping outputs nothing reads and inputs no live output
// needs must never change a bit. Randomised states and inputs; the reference is
// the compute-everything plan (plan_combiners(state, config, false)).
#include <doctest/doctest.h>

#include <random>
#include <string>
#include <vector>

#include "combiner_random_state.h"
#include "combiner_test_support.h"
#include "pipeline/combiners/describe.h"

using namespace ffsim;
using namespace ffsim::combiners;

namespace {

using test::kRegs;
using test::pick;
using test::random_state;

template <class V>
struct Inputs {
  std::vector<V> primary, secondary, fog, tex[4];
  bool has_secondary = true, has_fog = true, enabled[4] = {true, true, true, true};
};

template <class V>
CombinerInputs<V> view(const Inputs<V>& d, int count, const CombinerPlan* plan) {
  // With a plan, inputs the plan does not read are withheld (nullptr) to prove it.
  CombinerInputs<V> in;
  in.count = count;
  in.primary = !plan || plan->primary_needed ? d.primary.data() : nullptr;
  in.secondary = d.has_secondary && (!plan || plan->secondary_needed) ? d.secondary.data() : nullptr;
  in.fog_factor = d.has_fog && (!plan || plan->fog_factor_needed) ? d.fog.data() : nullptr;
  for (std::size_t u = 0; u < 4; ++u)
    in.texture[u] = d.enabled[u] && (!plan || plan->texture_needed[u]) ? d.tex[u].data() : nullptr;
  return in;
}

void compare_fixed(const Profile& profile, int iterations, unsigned seed) {
  std::mt19937 rng(seed);
  CombinerConfig cfg = CombinerConfig::from_profile(profile);
  constexpr int kCount = 64;
  int skipped_portions = 0, withheld_textures = 0;
  for (int it = 0; it < iterations; ++it) {
    cfg.rounding = rng() % 2 ? CombinerRounding::PerProduct : CombinerRounding::PerStage;
    cfg.rc2_secondary_alpha = rng() % 2;
    const CombinerState s = random_state(rng, cfg);
    const CombinerPlan planned = plan_combiners(s, cfg), full = plan_combiners(s, cfg, false);
    for (const PlannedStage& st : planned.stages) skipped_portions += !st.rgb.run + !st.alpha.run;
    for (int u = 0; u < cfg.texture_units; ++u) withheld_textures += !planned.texture_needed[static_cast<std::size_t>(u)];
    Inputs<std::uint16_t> d;
    const std::uint32_t cmax = (1u << cfg.color_bits) - 1, tmax = (1u << cfg.texture_bits) - 1;
    auto fill = [&](std::vector<std::uint16_t>& v, std::size_t n, std::uint32_t max) {
      v.resize(n);
      for (auto& x : v) x = static_cast<std::uint16_t>(rng() % 4 == 0 ? (rng() % 2) * max : rng() % (max + 1));
    };
    fill(d.primary, 4 * kCount, cmax);
    fill(d.secondary, 4 * kCount, cmax);
    fill(d.fog, kCount, cmax);
    for (auto& t : d.tex) fill(t, 4 * kCount, tmax);
    d.has_secondary = rng() % 4 != 0;
    d.has_fog = rng() % 2;
    for (int u = 0; u < 4; ++u) d.enabled[u] = u < cfg.texture_units && rng() % 4 != 0;
    const std::array<double, 4> fog_color{0.25, 0.5, 0.75, 1.0};
    std::vector<std::uint16_t> a(4 * kCount), b(4 * kCount);
    shade_span(planned, view(d, kCount, &planned), fog_color, a.data());
    shade_span(full, view(d, kCount, nullptr), fog_color, b.data());
    if (a != b) {
      FAIL_CHECK("planned != full, iteration " << it << ", profile " << profile.name << "\n" << describe(full));
      return;
    }
  }
  CHECK(skipped_portions > 0);
  CHECK(withheld_textures > 0);
}

void compare_float(const Profile& profile, int iterations, unsigned seed) {
  std::mt19937 rng(seed);
  const CombinerConfig cfg = CombinerConfig::from_profile(profile);
  std::uniform_real_distribution<double> u(0, 1);
  constexpr int kCount = 32;
  for (int it = 0; it < iterations; ++it) {
    const CombinerState s = random_state(rng, cfg);
    const CombinerPlan planned = plan_combiners(s, cfg), full = plan_combiners(s, cfg, false);
    Inputs<double> d;
    auto fill = [&](std::vector<double>& v, std::size_t n) {
      v.resize(n);
      for (auto& x : v) x = rng() % 4 == 0 ? static_cast<double>(rng() % 2) : u(rng);
    };
    fill(d.primary, 4 * kCount);
    fill(d.secondary, 4 * kCount);
    fill(d.fog, kCount);
    for (auto& t : d.tex) fill(t, 4 * kCount);
    d.has_fog = rng() % 2;
    for (int k = 0; k < 4; ++k) d.enabled[k] = rng() % 4 != 0;
    const std::array<double, 4> fog_color{0.25, 0.5, 0.75, 1.0};
    std::vector<double> a(4 * kCount), b(4 * kCount);
    shade_span(planned, view(d, kCount, &planned), fog_color, a.data());
    shade_span(full, view(d, kCount, nullptr), fog_color, b.data());
    if (a != b) {
      FAIL_CHECK("planned != full (float), iteration " << it << "\n" << describe(full));
      return;
    }
  }
}

}  // namespace

TEST_CASE("combiner plan: planned == compute-everything, bit-identical, geforce256 (random states and inputs)") {
  compare_fixed(*find_builtin_profile("geforce256"), 3000, 1);
}

TEST_CASE("combiner plan: planned == compute-everything, rgba10 and rgba12 (8 stages, 4 units, wide accumulators)") {
  compare_fixed(*find_builtin_profile("rgba10"), 1000, 2);
  compare_fixed(*find_builtin_profile("rgba12"), 1000, 3);
}

TEST_CASE("combiner plan: planned == compute-everything with colour and texel widths off the register grid") {
  Profile p = *find_builtin_profile("geforce256");
  p.color_bits = 6;
  p.texture_bits = 5;
  p.combiner_bits = 10;
  compare_fixed(p, 1000, 4);
}

TEST_CASE("combiner plan: planned == compute-everything, float32 and ideal") {
  compare_float(*find_builtin_profile("float32"), 1000, 5);
  compare_float(*find_builtin_profile("ideal"), 1000, 6);
}

TEST_CASE("combiner plan: the initial state reads primary and secondary colour and fog, no texture") {
  const CombinerPlan p = plan_combiners(CombinerState{}, test::geforce_config());
  CHECK(p.primary_needed);
  CHECK(p.secondary_needed);
  CHECK(p.fog_factor_needed);
  for (bool t : p.texture_needed) CHECK_FALSE(t);
  // RC Tables .5/.6: spare0 = primary, fcoc = fog.a * (spare0 + secondary) + (1 - fog.a) * fog.rgb.
  CHECK(describe(p) ==
        "stage 0 rgb:   spare0.rgb = primary.rgb\n"
        "stage 0 alpha: spare0.a = primary.a\n"
        "final:         fcoc.rgb = fog.a * min(max(spare0.rgb, 0) + secondary.rgb, 1) + (1 - fog.a) * fog.rgb\n"
        "               fcoc.a = max(spare0.a, 0)\n");
  // Shading with those defaults: fog disabled (FOG alpha = 1) gives clamp(primary + secondary).
  test::Fragment f;
  for (int c = 0; c < 4; ++c) f.primary[c] = static_cast<std::uint16_t>(60 * c + 10), f.secondary[c] = 200;
  const auto out = test::shade_one(p, f);
  CHECK(out[0] == 210);
  CHECK(out[1] == 255);
  CHECK(out[3] == 190);
}

TEST_CASE("combiner plan: SPARE0 alpha starts as texture 0 alpha, so reading it samples unit 0") {
  CombinerState s;
  s.final_var[6] = VariableState{gl::SPARE0_NV, gl::UNSIGNED_IDENTITY_NV, gl::ALPHA};
  s.stages[0].alpha.sum_output = gl::DISCARD_NV;  // stage 0 leaves spare0.a alone
  const CombinerPlan p = plan_combiners(s, test::geforce_config());
  CHECK(p.texture_needed[0]);
  CHECK_FALSE(p.texture_needed[1]);
  CHECK_FALSE(p.stages[0].alpha.run);
  test::Fragment f;
  f.tex[0][3] = 99;
  CHECK(test::shade_one(p, f)[3] == 99);
  f.tex_enabled[0] = false;  // undefined -> 0 (choice #24)
  CHECK(test::shade_one(p, f)[3] == 0);
}

TEST_CASE("combiner plan: RC2 per-stage constants in general stages, global ones in the final combiner") {
  CombinerState s;
  s.per_stage_constants = true;
  s.constant_color0 = {0.2, 0.2, 0.2, 0.2};
  s.stages[0].constant_color0 = {0.6, 0.6, 0.6, 0.6};
  s.stages[0].rgb.var[0] = VariableState{gl::CONSTANT_COLOR0_NV, gl::UNSIGNED_IDENTITY_NV, gl::RGB};
  s.final_var[0] = VariableState{gl::ZERO, gl::UNSIGNED_INVERT_NV, gl::RGB};       // A = 1
  s.final_var[1] = VariableState{gl::SPARE0_NV, gl::UNSIGNED_IDENTITY_NV, gl::RGB};  // B = spare0 = stage 0's ccc0
  s.final_var[6] = VariableState{gl::CONSTANT_COLOR0_NV, gl::UNSIGNED_IDENTITY_NV, gl::ALPHA};
  test::Fragment f;
  auto out = test::shade_one(plan_combiners(s, test::geforce_config()), f);
  CHECK(out[0] == 153);  // 0.6 * 255
  CHECK(out[3] == 51);   // 0.2 * 255: the final combiner reads the global constant
  s.per_stage_constants = false;
  out = test::shade_one(plan_combiners(s, test::geforce_config()), f);
  CHECK(out[0] == 51);
}

TEST_CASE("combiner plan: SECONDARY_COLOR alpha is 0 (NV1x, choice #24) or the secondary alpha (RC2 v1.2)") {
  CombinerState s;
  s.final_var[6] = VariableState{gl::SECONDARY_COLOR_NV, gl::UNSIGNED_IDENTITY_NV, gl::ALPHA};
  CombinerConfig cfg = test::geforce_config();
  test::Fragment f;
  f.secondary[3] = 123;
  CHECK(test::shade_one(plan_combiners(s, cfg), f)[3] == 0);
  cfg.rc2_secondary_alpha = true;
  CHECK(test::shade_one(plan_combiners(s, cfg), f)[3] == 123);
}

TEST_CASE("combiner plan: constants and fog colour enter as 8-bit codes, 0.5 -> 128 (choice #36)") {
  CombinerState s;
  s.constant_color0 = {0.5, 0.5, 0.5, 0.5};
  const CombinerPlan p = plan_combiners(s, test::geforce_config());
  CHECK(p.constant_codes[0][0] == 128);
  // FOG rgb with fog disabled (FOG alpha = 1 -> C weight 0) cannot be seen; read it through D.
  s.final_var[3] = VariableState{gl::FOG, gl::UNSIGNED_IDENTITY_NV, gl::RGB};
  s.final_var[0] = VariableState{gl::ZERO, gl::UNSIGNED_IDENTITY_NV, gl::RGB};
  s.final_var[2] = VariableState{gl::ZERO, gl::UNSIGNED_IDENTITY_NV, gl::RGB};
  s.final_var[6] = VariableState{gl::FOG, gl::UNSIGNED_IDENTITY_NV, gl::ALPHA};
  test::Fragment f;
  auto out = test::shade_one(plan_combiners(s, test::geforce_config()), f, {0.5, 0.25, 1.0, 0.0});
  CHECK(out[0] == 128);
  CHECK(out[1] == 64);  // 63.75 -> 64
  CHECK(out[2] == 255);
  CHECK(out[3] == 255);  // fog disabled: FOG alpha = 1
  f.fog = true;
  f.fog_factor = 40;
  CHECK(test::shade_one(plan_combiners(s, test::geforce_config()), f)[3] == 40);
}

TEST_CASE("combiner registers: texture register components by base format (RC Table NV_register_combiners.2)") {
  const std::uint16_t c[4] = {10, 20, 30, 40};
  using A = std::array<std::uint16_t, 4>;
  CHECK(texture_register_rgba<std::uint16_t>(BaseFormat::Alpha, c, 255) == A{0, 0, 0, 10});
  CHECK(texture_register_rgba<std::uint16_t>(BaseFormat::Luminance, c, 255) == A{10, 10, 10, 255});
  CHECK(texture_register_rgba<std::uint16_t>(BaseFormat::LuminanceAlpha, c, 255) == A{10, 10, 10, 20});
  CHECK(texture_register_rgba<std::uint16_t>(BaseFormat::Intensity, c, 255) == A{10, 10, 10, 10});
  CHECK(texture_register_rgba<std::uint16_t>(BaseFormat::RGB, c, 255) == A{10, 20, 30, 255});
  CHECK(texture_register_rgba<std::uint16_t>(BaseFormat::RGBA, c, 255) == A{10, 20, 30, 40});
}

TEST_CASE("combiner registers: register names and indices round trip") {
  for (int i = 0; i <= kSpare0PlusSecondary; ++i) CHECK(register_index(register_enum(i)) == i);
  CHECK(register_index(gl::DISCARD_NV) == -1);
  CHECK(std::string(register_short_name(kTexture1)) == "tex1");
}
