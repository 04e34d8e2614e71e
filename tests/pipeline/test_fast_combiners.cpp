// The register combiners' span kernel (pipeline/combiners/combiner_span.cpp)
// against the generic shade_span: random combiner states (every stage count,
// mapping, output, scale, bias, dot, mux, per-stage constants, both rounding
// modes, RC2 secondary alpha) and random inputs (spans of 1..200 fragments, so
// chunk boundaries are crossed), in every fixed profile and at widths off the
// register grid. Outputs must be identical.
#include <doctest/doctest.h>

#include <functional>
#include <random>
#include <vector>

#include "combiner_random_state.h"
#include "combiner_test_support.h"
#include "pipeline/combiners/combiner_span.h"
#include "pipeline/combiners/describe.h"

using namespace ffsim;
using namespace ffsim::combiners;

namespace {

using test::kRegs;
using test::pick;
using test::random_state;

struct Case {
  CombinerPlan plan;
  std::vector<std::uint16_t> primary, secondary, fog, tex[4];
  CombinerInputsFixed in;
};

// `edit` may change the random state before it is planned.
Case random_case(std::mt19937& rng, CombinerConfig cfg, bool skip_dead,
                 const std::function<void(CombinerState&)>& edit = {}) {
  Case c;
  cfg.rounding = rng() % 2 ? CombinerRounding::PerProduct : CombinerRounding::PerStage;
  cfg.rc2_secondary_alpha = rng() % 2;
  CombinerState state = random_state(rng, cfg);
  if (edit) edit(state);
  c.plan = plan_combiners(state, cfg, skip_dead);
  const int count = 1 + static_cast<int>(rng() % 200);
  const std::uint32_t cmax = (1u << cfg.color_bits) - 1, tmax = (1u << cfg.texture_bits) - 1;
  auto fill = [&](std::vector<std::uint16_t>& v, std::size_t n, std::uint32_t max) {
    v.resize(n);
    for (auto& x : v) x = static_cast<std::uint16_t>(rng() % 4 == 0 ? (rng() % 2) * max : rng() % (max + 1));
  };
  fill(c.primary, 4 * static_cast<std::size_t>(count), cmax);
  fill(c.secondary, 4 * static_cast<std::size_t>(count), cmax);
  fill(c.fog, static_cast<std::size_t>(count), cmax);
  for (auto& t : c.tex) fill(t, 4 * static_cast<std::size_t>(count), tmax);
  c.in.count = count;
  c.in.primary = c.primary.data();
  c.in.secondary = rng() % 4 ? c.secondary.data() : nullptr;
  c.in.fog_factor = rng() % 2 ? c.fog.data() : nullptr;
  for (std::size_t u = 0; u < 4; ++u)
    c.in.texture[u] = static_cast<int>(u) < cfg.texture_units && rng() % 4 ? c.tex[u].data() : nullptr;
  return c;
}

void compare(const Profile& profile, int iterations, unsigned seed,
             const std::function<void(CombinerState&, std::mt19937&)>& edit = {}) {
  std::mt19937 rng(seed);
  const CombinerConfig cfg = CombinerConfig::from_profile(profile);
  for (int it = 0; it < iterations; ++it) {
    std::function<void(CombinerState&)> e;
    if (edit) e = [&](CombinerState& st) { edit(st, rng); };
    const Case c = random_case(rng, cfg, it % 4 != 0, e);
    const std::array<double, 4> fog_color{0.25, 0.5, 0.75, 1.0};
    std::vector<std::uint16_t> generic(4 * static_cast<std::size_t>(c.in.count)), fast(generic.size(), 7);
    shade_span(c.plan, c.in, fog_color, generic.data());
    REQUIRE(shade_span_fast(c.plan, c.in, fog_color, fast.data()));
    if (generic != fast) {
      FAIL_CHECK("fast != generic, iteration " << it << ", profile " << profile.name << ", bits " << cfg.combiner_bits
                                              << "\n" << describe(c.plan));
      return;
    }
  }
}

}  // namespace

TEST_CASE("fast combiners: span kernel == shade_span, geforce256") {
  compare(*find_builtin_profile("geforce256"), 1500, 11);
}

TEST_CASE("fast combiners: span kernel == shade_span, rgba10 and rgba12 (8 stages, 4 units, 128-bit final)") {
  compare(*find_builtin_profile("rgba10"), 500, 12);
  compare(*find_builtin_profile("rgba12"), 500, 13);
}

TEST_CASE("fast combiners: span kernel == shade_span at widths off the register grid and a run-time M") {
  Profile p = *find_builtin_profile("geforce256");
  p.color_bits = 6;
  p.texture_bits = 5;
  p.combiner_bits = 10;  // M = 511: not a compiled-in constant
  compare(p, 500, 14);
  p.color_bits = 10;
  p.texture_bits = 8;
  p.combiner_bits = 12;  // M = 2047: entry conversion widens colours, narrows nothing
  compare(p, 300, 15);
}

TEST_CASE("fast combiners: a final combiner whose A..D are ZERO (one RGB for the span), every mapping, spans across chunks") {
  // The kernel computes that RGB once per span and stores it with each fragment's
  // alpha; ZERO inverted is 1, so A·B + (1 − A)·C + D takes the values 0, 1 and 2.
  auto zero_abcd = [](CombinerState& st, std::mt19937& rng) {
    for (std::size_t v = 0; v < 4; ++v)
      st.final_var[v] = VariableState{gl::ZERO, rng() % 2 ? gl::UNSIGNED_IDENTITY_NV : gl::UNSIGNED_INVERT_NV, gl::RGB};
  };
  compare(*find_builtin_profile("geforce256"), 400, 18, zero_abcd);
  compare(*find_builtin_profile("rgba12"), 200, 19, zero_abcd);
}

TEST_CASE("fast combiners: float profiles are left to shade_span") {
  std::mt19937 rng(16);
  const CombinerConfig cfg = CombinerConfig::from_profile(*find_builtin_profile("float32"));
  const CombinerPlan plan = plan_combiners(random_state(rng, cfg), cfg);
  CombinerInputsFixed in;
  in.count = 1;
  std::uint16_t out[4] = {1, 2, 3, 4};
  CHECK_FALSE(shade_span_fast(plan, in, {0, 0, 0, 0}, out));
  CHECK(out[0] == 1);
}

TEST_CASE("fast combiners: a planted difference is detected") {
  // The comparison sees a change of one planned scale in the kernel's plan.
  std::mt19937 rng(17);
  const CombinerConfig cfg = CombinerConfig::from_profile(*find_builtin_profile("geforce256"));
  int differing = 0;
  for (int it = 0; it < 200; ++it) {
    Case c = random_case(rng, cfg, true);
    std::vector<std::uint16_t> generic(4 * static_cast<std::size_t>(c.in.count)), fast(generic.size());
    shade_span(c.plan, c.in, {0, 0, 0, 0}, generic.data());
    for (PlannedStage& st : c.plan.stages) st.rgb.scale2 = st.rgb.scale2 == 2 ? 4 : 2;
    shade_span_fast(c.plan, c.in, {0, 0, 0, 0}, fast.data());
    differing += generic != fast;
  }
  CHECK(differing > 20);
}
