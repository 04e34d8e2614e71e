// The shading stages of one fragment, in two separable steps (GL121 §3.8, §3.9;
// NV_register_combiners §3.8.11 keeps texture fetching when combiners replace
// the texture environments):
//   1. fetch_texels: the filtered texel of every texture unit the plan samples;
//   2. texture_environments: the texenv chain over units 0..n-1, then the colour
//      sum, producing the fragment colour.
// A register-combiner stage consumes the output of step 1 and the fragment's
// primary/secondary colours (Rgba) in place of step 2.
//
// The plan (design guide "Skip what a scene does not need") lists which units
// are sampled and which environments run: a unit that is disabled or whose
// texture is incomplete does nothing; a unit whose result no later stage reads
// (a later REPLACE/COMBINE that ignores PREVIOUS) is neither sampled nor
// evaluated; a COMBINE that reads no TEXTURE source is evaluated but not sampled.
// Skipping never changes an output bit (tests compare with full_shading_plan).
#pragma once
#include <array>
#include <string>

#include "pipeline/texenv/texenv.h"
#include "pipeline/texture/texture_sample.h"

namespace ffsim {

inline constexpr int kShadeUnits = 4;

// One texture unit as shading sees it, resolved from GL state by the context.
struct ShadeUnit {
  const TextureObject* texture = nullptr;  // enabled (2D over 1D) and complete; nullptr: unit disabled
  int dims = 2;                            // 1 or 2
  TexEnvState env;
};

struct ShadingState {
  ColorFormat color;
  SampleFormat sample;
  std::array<ShadeUnit, kShadeUnits> units{};
  int unit_count = kShadeUnits;  // MAX_TEXTURE_UNITS of the profile (units beyond stay disabled)
  bool color_sum = false;        // COLOR_SUM enabled
};

struct ShadingPlan {
  std::array<bool, kShadeUnits> sample{};  // fetch the unit's filtered texel
  std::array<bool, kShadeUnits> env{};     // evaluate the unit's environment
  bool color_sum = false;
  bool any_texturing() const;
  bool operator==(const ShadingPlan&) const = default;
};

// Plan with every skip applied.
ShadingPlan plan_shading(const ShadingState& st);
// Plan that runs every enabled unit and the colour sum when enabled: the
// reference the planned path must match.
ShadingPlan full_shading_plan(const ShadingState& st);
// One line per stage: what runs and what was skipped, with the reason.
std::string explain_shading(const ShadingState& st, const ShadingPlan& plan);

// Texture coordinates of one fragment on one unit: s/q, t/q and λ.
struct FragmentTexCoord {
  double s = 0, t = 0, lambda = 0;
};
using UnitTexCoords = std::array<FragmentTexCoord, kShadeUnits>;
using UnitTexels = std::array<Texel, kShadeUnits>;

// Step 1. Units the plan does not sample are left untouched in `out`.
void fetch_texels(const ShadingState& st, const ShadingPlan& plan, const UnitTexCoords& tc, UnitTexels& out);

// Step 2. Texture environments of the planned units in order (a unit that does
// not run passes its input through), then the colour sum when planned.
Rgba texture_environments(const ShadingState& st, const ShadingPlan& plan, const Rgba& primary,
                          const Rgba& secondary, const UnitTexels& texels);

}  // namespace ffsim
