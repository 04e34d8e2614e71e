// A random legal register-combiner state (every register, mapping, usage,
// output, scale, bias, dot and mux the extension allows for cfg), shared by the
// plan test (test_combiner_plan.cpp) and the span-kernel test (test_fast_combiners.cpp).
#pragma once
#include <cstddef>
#include <random>

#include "combiner_test_support.h"
#include "pipeline/combiners/describe.h"

namespace ffsim::test {

using namespace ffsim::combiners;

const GLenum kRegs[] = {gl::ZERO,        gl::CONSTANT_COLOR0_NV, gl::CONSTANT_COLOR1_NV, gl::FOG,
                        gl::PRIMARY_COLOR_NV, gl::SECONDARY_COLOR_NV, gl::SPARE0_NV, gl::SPARE1_NV,
                        gl::TEXTURE0,    gl::TEXTURE1,           gl::TEXTURE2,           gl::TEXTURE3};
const GLenum kOuts[] = {gl::DISCARD_NV, gl::DISCARD_NV, gl::DISCARD_NV, gl::PRIMARY_COLOR_NV, gl::SECONDARY_COLOR_NV,
                        gl::SPARE0_NV,  gl::SPARE1_NV,  gl::TEXTURE0,   gl::TEXTURE1,         gl::TEXTURE2,
                        gl::TEXTURE3};
const GLenum kScales[] = {gl::NONE, gl::SCALE_BY_TWO_NV, gl::SCALE_BY_FOUR_NV, gl::SCALE_BY_ONE_HALF_NV};

template <class T, std::size_t N>
inline T pick(std::mt19937& rng, const T (&a)[N], std::size_t n = N) {
  return a[rng() % n];
}

inline CombinerState random_state(std::mt19937& rng, const CombinerConfig& cfg) {
  const std::size_t nregs = 8 + static_cast<std::size_t>(cfg.texture_units);
  const std::size_t nouts = 7 + static_cast<std::size_t>(cfg.texture_units);
  std::uniform_real_distribution<double> u(0, 1);
  CombinerState s;
  s.num_general_combiners = 1 + static_cast<int>(rng() % static_cast<unsigned>(cfg.general_combiners));
  s.color_sum_clamp = rng() % 2;
  s.per_stage_constants = rng() % 3 == 0;
  for (auto* c : {&s.constant_color0, &s.constant_color1})
    for (double& x : *c) x = u(rng);
  for (int i = 0; i < cfg.general_combiners; ++i) {
    GeneralStageState& st = s.stages[static_cast<std::size_t>(i)];
    for (auto* c : {&st.constant_color0, &st.constant_color1})
      for (double& x : *c) x = u(rng);
    for (int portion = 0; portion < 2; ++portion) {
      PortionState& p = portion == 0 ? st.rgb : st.alpha;
      const GLenum pe = portion == 0 ? gl::RGB : gl::ALPHA;
      for (auto& v : p.var) {
        do {
          const GLenum usages_rgb[] = {gl::RGB, gl::RGB, gl::ALPHA}, usages_a[] = {gl::ALPHA, gl::BLUE};
          v = VariableState{pick(rng, kRegs, nregs), pick(rng, test::kMappings),
                            portion == 0 ? pick(rng, usages_rgb) : pick(rng, usages_a)};
        } while (!check_combiner_input(pe, gl::VARIABLE_A_NV, v.input, v.mapping, v.component_usage, cfg.texture_units));
      }
      do {
        p.ab_output = pick(rng, kOuts, nouts);
        p.cd_output = pick(rng, kOuts, nouts);
        p.sum_output = pick(rng, kOuts, nouts);
        p.scale = pick(rng, kScales);
        p.bias = rng() % 3 == 0 ? gl::BIAS_BY_NEGATIVE_ONE_HALF_NV : gl::NONE;
        p.ab_dot_product = portion == 0 && rng() % 3 == 0;
        p.cd_dot_product = portion == 0 && rng() % 3 == 0;
        p.mux_sum = rng() % 3 == 0;
      } while (!check_combiner_output(pe, p.ab_output, p.cd_output, p.sum_output, p.scale, p.bias, p.ab_dot_product,
                                      p.cd_dot_product, cfg.texture_units));
    }
  }
  const GLenum final_inputs[] = {gl::ZERO,          gl::CONSTANT_COLOR0_NV, gl::CONSTANT_COLOR1_NV, gl::FOG,
                                 gl::PRIMARY_COLOR_NV, gl::SECONDARY_COLOR_NV, gl::SPARE0_NV,     gl::SPARE1_NV,
                                 gl::TEXTURE0,      gl::TEXTURE1,           gl::E_TIMES_F_NV,       gl::SPARE0_PLUS_SECONDARY_COLOR_NV,
                                 gl::SPARE0_NV,     gl::SPARE1_NV};
  const GLenum usages[] = {gl::RGB, gl::ALPHA, gl::BLUE};
  for (std::size_t v = 0; v < 7; ++v) {
    VariableState& f = s.final_var[v];
    do {
      f = VariableState{pick(rng, final_inputs), rng() % 2 ? gl::UNSIGNED_IDENTITY_NV : gl::UNSIGNED_INVERT_NV,
                        pick(rng, usages)};
    } while (!check_final_combiner_input(gl::VARIABLE_A_NV + static_cast<GLenum>(v), f.input, f.mapping,
                                         f.component_usage, cfg.texture_units));
  }
  return s;
}

}  // namespace ffsim::test
