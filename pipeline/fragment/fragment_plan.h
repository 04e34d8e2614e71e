// The per-fragment operations as a plan (docs/architecture.md "Skip what a scene
// does not need"; GL 1.2.1 §4.1 order: ownership, scissor, alpha test, stencil
// test, depth test, blending or logic op, dithering, masked writes).
//
// Per draw: the GL state (FragmentOpsState) and the buffer format (FragmentTarget)
// are reduced to a canonical FragmentPlanKey (every bit that cannot change the
// result cleared), and reference values, masks, the blend colour and the scissor
// box go into FragmentConstants. The key determines a FragmentPlan holding only
// the stages that do something; callers cache plans by key.
//
// Two paths write a span into the buffers:
//  - run_fragment_plan: only the plan's stages, each a simple loop specialised by
//    the plan (no destination colour read unless a channel needs it, no work on
//    channels the colour mask discards or that keep the destination);
//  - run_fragment_ops_full: the reference interpreter, every stage evaluated from
//    the raw state for every fragment and every channel. Tests assert that both
//    produce identical buffers.
#pragma once
#include <array>
#include <cstdint>
#include <string>

#include "pipeline/fragment/alpha_test.h"
#include "pipeline/fragment/blend.h"
#include "pipeline/fragment/blend_lanes8.h"
#include "pipeline/fragment/depth.h"
#include "pipeline/fragment/fragment_span.h"
#include "pipeline/fragment/logic_op.h"
#include "pipeline/fragment/scissor.h"
#include "pipeline/fragment/stencil.h"
#include "pipeline/fragment/test_func.h"
#include "pipeline/fragment/write_mask.h"
#include "pipeline/number/profile.h"

namespace ffsim {

struct FragmentOpsState {
  ScissorBox scissor;
  AlphaTestState alpha;
  StencilState stencil;
  DepthState depth;
  BlendState blend;
  LogicOpState logic;
  bool dither = true;  // GL initial state; identity here (write_mask.h)
  std::array<bool, 4> color_mask{true, true, true, true};
  std::uint32_t stencil_writemask = 0xFFFFFFFFu;
  bool depth_mask = true;
  bool operator==(const FragmentOpsState&) const = default;
};

// The buffers' format: window size, colour arithmetic and widths.
struct FragmentTarget {
  int width = 0, height = 0;
  Arithmetic arith = Arithmetic::Fixed;
  int color_bits = 8;    // fixed colour code width
  int stencil_bits = 8;  // 0: no stencil buffer
  int depth_bits = 24;   // 0: no depth buffer
};

// The buffers (whole window, rows bottom to top, width pixels per row). Exactly
// one of codes/values is used, by arithmetic; stencil/depth null when absent.
struct FragmentBuffers {
  std::uint16_t* codes = nullptr;  // 4 per pixel, fixed colour
  double* values = nullptr;        // 4 per pixel, float colour
  std::uint8_t* stencil = nullptr;
  std::uint32_t* depth = nullptr;
};

// What a channel's final write computes (after blending/logic-op simplification).
enum class ChannelOp : std::uint8_t {
  Keep,    // not written (colour mask off, or the result is the destination)
  Zero,    // constant 0 (e.g. FUNC_SUBTRACT with a ZERO source factor)
  Copy,    // the source value
  SrcTerm, // Cs*S alone
  DstTerm, // Cd*D alone
  Add,     // min(1, Cs*S + Cd*D)
  Sub,     // max(0, Cs*S - Cd*D)
  RevSub,  // max(0, Cd*D - Cs*S)
  Min,
  Max,
  Logic,   // logic op on codes (fixed profiles)
};

// Canonical state key: only what selects the stages and their kernels. Fields of
// inactive stages are zero; comparisons are by value.
struct FragmentPlanKey {
  Arithmetic arith = Arithmetic::Fixed;
  bool nothing = false;  // no fragment can change any buffer (all other fields zero)
  GLenum alpha_func = 0; // 0: no alpha test
  bool stencil = false;
  GLenum stencil_func = 0, sfail = 0, dpfail = 0, dppass = 0;
  bool depth = false;
  GLenum depth_func = 0;
  bool depth_write = false;
  std::array<ChannelOp, 4> channel{ChannelOp::Keep, ChannelOp::Keep, ChannelOp::Keep, ChannelOp::Keep};
  GLenum blend_src = 0, blend_dst = 0;  // 0 when no channel's operation uses the factor
  GLenum logic_op = 0;                                      // 0 when no channel uses the logic op
  auto operator<=>(const FragmentPlanKey&) const = default;
};

// Per-draw numbers, kept out of the key.
struct FragmentConstants {
  WriteRect rect;                 // window intersected with the scissor box
  int color_bits = 8;
  std::uint32_t color_max = 255;  // M = 2^m - 1
  std::uint32_t alpha_ref_code = 0;
  double alpha_ref_value = 0;
  std::uint32_t stencil_max = 0, stencil_ref = 0, stencil_value_mask = 0, stencil_writemask = 0;
  std::array<std::uint32_t, 4> blend_color_code{0, 0, 0, 0};
  std::array<double, 4> blend_color_value{0, 0, 0, 0};  // binary32-rounded for Float32
  std::array<double, 4> blend_color_given{0, 0, 0, 0};
  // The stencil test and operations of the plan key built from the same state,
  // tabulated over all 256 stored values (fragment_constants; valid when the key
  // has the stencil test and a stencil buffer of at most 8 bits): pass[v] is the
  // test's result for stored value v, after_*[v] the value then written (through
  // the write mask). The fragment operations use them when the plan's function and
  // operations are these (else they compute per fragment; the same values).
  struct StencilTables {
    bool valid = false;
    GLenum func = 0, sfail = 0, dpfail = 0, dppass = 0;
    std::array<std::uint8_t, 256> pass{}, after_sfail{}, after_dpfail{}, after_dppass{};
  } stencil_tables;
};

struct FragmentPlan {
  FragmentPlanKey key;
  bool read_dst_color = false;  // some written channel reads the destination colour
  bool write_color = false;     // some channel is written
  BlendLanes8 lanes8;           // the 8-bit colour stage's lane pattern (blend_lanes8.h)
};

FragmentPlanKey fragment_plan_key(const FragmentOpsState& s, const FragmentTarget& t);
FragmentPlan build_fragment_plan(const FragmentPlanKey& key);
FragmentConstants fragment_constants(const FragmentOpsState& s, const FragmentTarget& t);

// The plan's stencil test writes nothing: its three operations are KEEP (the
// key holds KEEP for all three when the write mask is 0).
inline bool stencil_ops_kept(const FragmentPlanKey& key) {
  return key.sfail == gl::KEEP && key.dpfail == gl::KEEP && key.dppass == gl::KEEP;
}
// The depth test is the only stage that writes depth or stencil: no stencil
// test, or one that writes nothing (then only a mask before the depth test).
inline bool depth_test_alone(const FragmentPlanKey& key) {
  return key.depth && (!key.stencil || stencil_ops_kept(key));
}

// The depth test's comparisons of a list of fragments, to be reused
// (docs/performance.md 17.1). The depth test alone (no stencil test) makes a
// fragment survive when it is alive and z OP stored holds: with the same
// fragments (pixels and depth codes), the same function and the same stored
// values, the comparisons are the same, and when no fragment passing them has a
// depth other than the stored one (or depth writes are off) nothing is stored.
struct ListedDepthTest {
  // In: the comparisons (1: z OP stored) of an earlier call under exactly those
  // conditions, one byte per fragment. The depth buffer is then not read or
  // written. Used only when depth_test_alone(plan key) (a stencil test that
  // writes nothing is applied before it as a mask).
  const std::uint8_t* known = nullptr;
  // Out, when not `known`: the comparisons of this call into `record` (n bytes),
  // for the depth test alone; `recorded` says whether they were written.
  std::uint8_t* record = nullptr;
  bool recorded = false;
  bool would_store = false;  // out, when recorded: some fragment passing the comparison has z != stored
  bool stored = false;       // out: a stored depth may have changed (exact for the depth test alone)
};

// Apply the per-fragment operations to a span. The span's colour is codes at
// t.color_bits (fixed) or values (float); its depth holds one code per fragment
// and may be empty only when the plan has no depth test (else std::invalid_argument).
// Returns whether a stored depth may have changed (exact for the depth test
// alone: some fragment stored a depth other than the one there).
bool run_fragment_plan(const FragmentPlan& plan, const FragmentConstants& k, const FragmentSpan& span,
                       const FragmentBuffers& b, int width);
// run_fragment_plan for n fragments of one primitive at distinct pixels, all
// inside k.rect, in a fixed profile: fragment i has colour codes codes[4i .. 4i+3],
// depth depth[i] (may be null without a depth test) and lands on pixel index
// pixel[i] = y·width + x (below 2^26, the framebuffer's limit in sim/framebuffer.h;
// the AVX2 loops use them as 32-bit gather indices). No fragment reads another's pixel, so the buffers end
// as run_fragment_plan leaves them on the same fragments as row spans in any
// order. Throws std::invalid_argument for float colour or a missing depth.
// `depth_test` (may be null) takes known comparisons or records them.
void run_fragment_plan_pixels(const FragmentPlan& plan, const FragmentConstants& k, const std::uint16_t* codes,
                              const std::uint32_t* depth, const std::uint32_t* pixel, int n, const FragmentBuffers& b,
                              ListedDepthTest* depth_test = nullptr);
void run_fragment_ops_full(const FragmentOpsState& s, const FragmentTarget& t, const FragmentSpan& span,
                           const FragmentBuffers& b);

// The plan as text, one line per stage in GL order, with skipped stages named;
// blending shown as equations with trivial terms removed (`A = max(0, A_s - A_d)`).
std::string describe(const FragmentPlan& plan, const FragmentConstants& k);

}  // namespace ffsim
