// A random colour table for the pixel-transfer tests (test_pixel_plan.cpp,
// test_byte_texels.cpp): a random base format, a width of 1-256 entries and
// random entries in [0, 1] (binary32 values).
#pragma once
#include <random>

#include "pipeline/pixel_transfer/pixel_state.h"
#include "pipeline/texture/texture_object.h"

namespace ffsim::pixel::test {

inline ColorTable random_table(std::mt19937& rng, bool enabled) {
  ColorTable t;
  t.enabled = enabled;
  t.base = static_cast<BaseFormat>(rng() % 6);
  t.width = 1 << (rng() % 9);
  std::uniform_real_distribution<double> u(0, 1);
  for (int i = 0; i < t.width * component_count(t.base); ++i) t.entries.push_back(static_cast<float>(u(rng)));
  return t;
}

}  // namespace ffsim::pixel::test
