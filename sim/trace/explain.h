// `ffsim replay --explain`: after every pass (a draw, a copy or a clear) each
// registered explainer is asked to describe, in words or equations, what that pass
// did with the current state: the plan's stages run and skipped, the active
// combiner stages as equations, the blend. An area registers its explainer with
// one line in sim/trace/explain.cpp; an explainer returns "" when it has nothing
// to say about the pass.
#pragma once
#include <functional>
#include <string>
#include <vector>

#include "sim/context.h"
#include "sim/trace/trace.h"

namespace ffsim::trace {

struct PassInfo {
  int index = 0;     // 1-based pass number (of the last pass, for a call that is not one)
  const Step& step;  // the command that made the pass
  bool is_pass = true;  // false: a call marked explain_after (a texture upload), not a pass
};

// The Context is not const: the areas' plan accessors build and cache their plans
// (an explainer changes no GL state and raises no GL error).
using Explainer = std::function<std::string(Context&, const PassInfo&)>;

struct ExplainerDef {
  std::string area;  // "core", "pixel transfer", "combiners", ...
  Explainer explain;
};

class ExplainerRegistry {
 public:
  void add(std::string area, Explainer fn) { defs_.push_back({std::move(area), std::move(fn)}); }
  const std::vector<ExplainerDef>& all() const { return defs_; }

 private:
  std::vector<ExplainerDef> defs_;
};

// The explainers of this build, in the order they print.
const ExplainerRegistry& explainers();

// The core explainer: framebuffer writes (masks, scissor, the cleared buffers).
std::string explain_writes(const Context& ctx, const PassInfo& pass);
// The areas' explainers: the pixel transfer plan of DrawPixels/CopyPixels, the
// shading plan of draws, the per-fragment plan, the register-combiner equations
// (when REGISTER_COMBINERS_NV is enabled).
std::string explain_pixel_transfer(Context& ctx, const PassInfo& pass);
std::string explain_shading_pass(Context& ctx, const PassInfo& pass);
std::string explain_fragment_pass(Context& ctx, const PassInfo& pass);
std::string explain_combiners_pass(Context& ctx, const PassInfo& pass);

}  // namespace ffsim::trace
