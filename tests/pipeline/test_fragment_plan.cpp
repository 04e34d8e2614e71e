// The per-fragment plan: canonical state keys, skipped stages, the describe()
// text, and the equivalence of the planned path with the full path over every
// stage combination and many random states (docs/architecture.md property 4).
#include <doctest/doctest.h>

#include <algorithm>
#include <random>
#include <stdexcept>
#include <string>

#include "fragment_harness.h"
#include "pipeline/fragment/alpha_test.h"

using namespace ffsim;
using namespace ffsim::test;

namespace {

const FragmentTarget kT8 = target8(16, 2);

FragmentPlan plan_of(const FragmentOpsState& s, const FragmentTarget& t = kT8) {
  return build_fragment_plan(fragment_plan_key(s, t));
}
std::string text_of(const FragmentOpsState& s, const FragmentTarget& t = kT8) {
  return describe(plan_of(s, t), fragment_constants(s, t));
}
bool contains(const std::string& hay, const std::string& needle) { return hay.find(needle) != std::string::npos; }

constexpr GLenum kFuncs[] = {gl::NEVER, gl::LESS, gl::EQUAL, gl::LEQUAL, gl::GREATER, gl::NOTEQUAL, gl::GEQUAL, gl::ALWAYS};
constexpr GLenum kOps[] = {gl::KEEP, gl::ZERO, gl::REPLACE, gl::INCR, gl::DECR, gl::INVERT, gl::INCR_WRAP, gl::DECR_WRAP};
constexpr GLenum kEqs[] = {gl::FUNC_ADD, gl::FUNC_SUBTRACT, gl::FUNC_REVERSE_SUBTRACT, gl::MIN, gl::MAX};
constexpr GLenum kSrc[] = {gl::ZERO, gl::ONE, gl::DST_COLOR, gl::ONE_MINUS_DST_COLOR, gl::SRC_ALPHA,
                           gl::ONE_MINUS_SRC_ALPHA, gl::DST_ALPHA, gl::ONE_MINUS_DST_ALPHA, gl::CONSTANT_COLOR,
                           gl::ONE_MINUS_CONSTANT_COLOR, gl::CONSTANT_ALPHA, gl::ONE_MINUS_CONSTANT_ALPHA,
                           gl::SRC_ALPHA_SATURATE};
constexpr GLenum kDst[] = {gl::ZERO, gl::ONE, gl::SRC_COLOR, gl::ONE_MINUS_SRC_COLOR, gl::SRC_ALPHA,
                           gl::ONE_MINUS_SRC_ALPHA, gl::DST_ALPHA, gl::ONE_MINUS_DST_ALPHA, gl::CONSTANT_COLOR,
                           gl::ONE_MINUS_CONSTANT_COLOR, gl::CONSTANT_ALPHA, gl::ONE_MINUS_CONSTANT_ALPHA};

}  // namespace

TEST_CASE("plan key: state that cannot matter is cleared") {
  FragmentOpsState a, b;
  // Blend factors and equation with blending off; alpha function with the alpha test off.
  b.blend = {false, gl::DST_ALPHA, gl::SRC_COLOR, gl::FUNC_SUBTRACT, {0.3, 0.2, 0.1, 0.9}};
  b.alpha = {false, gl::LESS, 0.7};
  b.depth.func = gl::GREATER;  // depth test off
  b.stencil = {false, gl::EQUAL, 3, 0x0F, gl::INCR, gl::DECR, gl::INVERT};
  b.logic.op = gl::XOR;  // logic op off
  b.dither = false;      // identity either way
  CHECK(fragment_plan_key(a, kT8) == fragment_plan_key(b, kT8));
  // Stencil with write mask 0 and func ALWAYS does nothing: dropped.
  b.stencil.enabled = true;
  b.stencil.func = gl::ALWAYS;
  b.stencil_writemask = 0;
  CHECK(fragment_plan_key(a, kT8) == fragment_plan_key(b, kT8));
  // Depth ALWAYS without depth writes does nothing: dropped.
  b.depth = {true, gl::ALWAYS};
  b.depth_mask = false;
  CHECK(fragment_plan_key(a, kT8) == fragment_plan_key(b, kT8));
  // Enabled tests on buffers that do not exist are dropped.
  FragmentOpsState c;
  c.stencil = {true, gl::NEVER, 0, 0xFF, gl::ZERO, gl::ZERO, gl::ZERO};
  c.depth = {true, gl::NEVER};
  CHECK(fragment_plan_key(c, target8(16, 2, 0, 0)) == fragment_plan_key(a, target8(16, 2, 0, 0)));
  // (ONE, ZERO, FUNC_ADD) blending is a plain copy.
  b = a;
  b.blend.enabled = true;
  CHECK(fragment_plan_key(a, kT8) == fragment_plan_key(b, kT8));
  // MIN/MAX ignore the factors.
  FragmentOpsState m1, m2;
  m1.blend = {true, gl::SRC_ALPHA, gl::ONE, gl::MIN, {}};
  m2.blend = {true, gl::ONE, gl::DST_ALPHA, gl::MIN, {}};
  CHECK(fragment_plan_key(m1, kT8) == fragment_plan_key(m2, kT8));
  // A source term alone is the same operation under FUNC_ADD and FUNC_SUBTRACT.
  m1.blend = {true, gl::SRC_ALPHA, gl::ZERO, gl::FUNC_ADD, {}};
  m2.blend = {true, gl::SRC_ALPHA, gl::ZERO, gl::FUNC_SUBTRACT, {}};
  CHECK(fragment_plan_key(m1, kT8) == fragment_plan_key(m2, kT8));
  // ... but not under FUNC_REVERSE_SUBTRACT (0 - Cs*S clamps to 0).
  m2.blend.equation = gl::FUNC_REVERSE_SUBTRACT;
  CHECK(fragment_plan_key(m1, kT8) != fragment_plan_key(m2, kT8));
  CHECK(fragment_plan_key(m2, kT8).channel[0] == ChannelOp::Zero);
  // Constants are not in the key: alpha ref, stencil ref and masks, blend colour, scissor box.
  FragmentOpsState k1, k2;
  k1.alpha = {true, gl::GREATER, 0.1};
  k2.alpha = {true, gl::GREATER, 0.9};
  k1.blend = {true, gl::CONSTANT_COLOR, gl::ONE, gl::FUNC_ADD, {0.1, 0.2, 0.3, 0.4}};
  k2.blend = {true, gl::CONSTANT_COLOR, gl::ONE, gl::FUNC_ADD, {0.9, 0.8, 0.7, 0.6}};
  k1.scissor = {true, 0, 0, 3, 3};
  k2.scissor = {true, 5, 1, 9, 9};
  CHECK(fragment_plan_key(k1, kT8) == fragment_plan_key(k2, kT8));
}

TEST_CASE("plan: skipped work (destination reads, channels, whole draws)") {
  FragmentOpsState s;
  FragmentPlan p = plan_of(s);
  CHECK(p.write_color);
  CHECK(!p.read_dst_color);  // no blending: no destination read
  // Transparency needs the destination.
  s.blend = {true, gl::SRC_ALPHA, gl::ONE_MINUS_SRC_ALPHA, gl::FUNC_ADD, {}};
  CHECK(plan_of(s).read_dst_color);
  // A source-only term with a source factor: no destination read.
  s.blend = {true, gl::SRC_ALPHA, gl::ZERO, gl::FUNC_ADD, {}};
  p = plan_of(s);
  CHECK(!p.read_dst_color);
  CHECK(p.key.channel[0] == ChannelOp::SrcTerm);
  CHECK(p.key.channel[3] == ChannelOp::SrcTerm);
  // FUNC_SUBTRACT with a ZERO source factor is the constant 0: no destination read.
  s.blend = {true, gl::ZERO, gl::ONE, gl::FUNC_SUBTRACT, {}};
  p = plan_of(s);
  CHECK(!p.read_dst_color);
  CHECK(p.key.channel[1] == ChannelOp::Zero);
  // (ZERO, ONE, ADD) leaves the destination: nothing to do at all.
  s.blend = {true, gl::ZERO, gl::ONE, gl::FUNC_ADD, {}};
  CHECK(plan_of(s).key.nothing);
  // ... unless the depth buffer is written.
  s.depth = {true, gl::LESS};
  p = plan_of(s);
  CHECK(!p.key.nothing);
  CHECK(!p.write_color);
  CHECK(p.key.depth);
  // Colour mask: no work on masked channels.
  FragmentOpsState a;
  a.color_mask = {false, false, false, true};
  a.blend = {true, gl::ONE, gl::ONE, gl::FUNC_SUBTRACT, {}};
  p = plan_of(a);
  CHECK(p.key.channel[0] == ChannelOp::Keep);
  CHECK(p.key.channel[2] == ChannelOp::Keep);
  CHECK(p.key.channel[3] == ChannelOp::Sub);
  // Every fragment discarded: nothing.
  FragmentOpsState n;
  n.alpha = {true, gl::NEVER, 0};
  CHECK(plan_of(n).key.nothing);
  n = FragmentOpsState{};
  n.color_mask = {false, false, false, false};
  CHECK(plan_of(n).key.nothing);  // depth test off: no depth writes either
  // SRC_ALPHA_SATURATE: f for RGB, 1 for A.
  FragmentOpsState sat;
  sat.blend = {true, gl::SRC_ALPHA_SATURATE, gl::ZERO, gl::FUNC_ADD, {}};
  p = plan_of(sat);
  CHECK(p.key.channel[0] == ChannelOp::SrcTerm);
  CHECK(p.key.channel[3] == ChannelOp::Copy);
  CHECK(p.read_dst_color);
  // The logic op replaces blending on fixed colour and is ignored on float colour.
  FragmentOpsState lo;
  lo.logic = {true, gl::XOR};
  lo.blend = {true, gl::ONE, gl::ONE, gl::FUNC_ADD, {}};
  CHECK(plan_of(lo).key.channel[0] == ChannelOp::Logic);
  CHECK(plan_of(lo, FragmentTarget{16, 2, Arithmetic::Float64, 8, 8, 24}).key.channel[0] == ChannelOp::Add);
}

TEST_CASE("describe: blend equations with trivial terms removed") {
  // Paper §4.1.5 step 10 with an alpha-only colour mask: A = max(0, A_s - A_d).
  FragmentOpsState s;
  s.color_mask = {false, false, false, true};
  s.blend = {true, gl::ONE, gl::ONE, gl::FUNC_SUBTRACT, {}};
  std::string t = text_of(s);
  CHECK(contains(t, "  colour: A = max(0, A_s - A_d)\n"));
  CHECK(contains(t, "  colour: RGB kept (masked, or the equation leaves the destination)\n"));
  CHECK(contains(t, "  alpha test: skipped\n"));
  CHECK(contains(t, "  stencil test: skipped\n"));
  // Paper §4.2 step 12: (DST_ALPHA, ONE) doubling.
  s = FragmentOpsState{};
  s.blend = {true, gl::DST_ALPHA, gl::ONE, gl::FUNC_ADD, {}};
  CHECK(contains(text_of(s), "  colour: RGBA = min(1, RGBA_s*A_d + RGBA_d)\n"));
  // Step 19: (DST_ALPHA, DST_ALPHA) modulation.
  s.blend = {true, gl::DST_ALPHA, gl::DST_ALPHA, gl::FUNC_ADD, {}};
  CHECK(contains(text_of(s), "  colour: RGBA = min(1, RGBA_s*A_d + RGBA_d*A_d)\n"));
  // Transparency and SRC_ALPHA_SATURATE (RGB and A differ).
  s.blend = {true, gl::SRC_ALPHA_SATURATE, gl::ONE, gl::FUNC_ADD, {}};
  t = text_of(s);
  CHECK(contains(t, "  colour: RGB = min(1, RGB_s*min(A_s, 1 - A_d) + RGB_d)\n"));
  CHECK(contains(t, "  colour: A = min(1, A_s + A_d)\n"));
  // No blending: a copy without a destination read.
  t = text_of(FragmentOpsState{});
  CHECK(contains(t, "  colour: RGBA = RGBA_s\n"));
  CHECK(contains(t, "  destination colour read: no\n"));
  // Constant colour shown with its codes: 0.5 -> 128 (half up).
  s.blend = {true, gl::CONSTANT_ALPHA, gl::ZERO, gl::FUNC_ADD, {0, 0, 0, 0.5}};
  t = text_of(s);
  CHECK(contains(t, "  colour: RGBA = RGBA_s*A_c\n"));
  CHECK(contains(t, "as codes (0, 0, 0, 128)"));
  // The tests with their references.
  s = FragmentOpsState{};
  s.alpha = {true, gl::EQUAL, 0.0};
  s.stencil = {true, gl::ALWAYS, 0, 0xFF, gl::KEEP, gl::KEEP, gl::INCR};
  t = text_of(s);
  CHECK(contains(t, "  alpha test: pass if A_s == 0/255 (ref 0)\n"));
  CHECK(contains(t, "  stencil test: always passes; ops: pass INCR; write mask 0xff\n"));
  s.alpha = {true, gl::GEQUAL, 0.5};
  s.stencil = {true, gl::LESS, 0x13, 0x0F, gl::ZERO, gl::INVERT, gl::REPLACE};
  s.depth = {true, gl::LESS};
  t = text_of(s);
  CHECK(contains(t, "  alpha test: pass if A_s >= 128/255 (ref 0.5)\n"));
  CHECK(contains(t, "  stencil test: pass if (19 & 0xf) < (S & 0xf); ops: fail ZERO, depth fail INVERT, pass REPLACE; write mask 0xff\n"));
  CHECK(contains(t, "  depth test: pass if z < Z_d; writes z\n"));
  // Exact full text of one plan (the format the --explain output uses).
  s = FragmentOpsState{};
  s.scissor = {true, 2, 1, 4, 1};
  s.depth = {true, gl::LEQUAL};
  s.depth_mask = false;
  s.blend = {true, gl::ONE, gl::ONE, gl::FUNC_REVERSE_SUBTRACT, {}};
  CHECK(text_of(s) ==
        "per-fragment operations (8-bit colour codes):\n"
        "  scissor: x 2..5, y 1..1\n"
        "  alpha test: skipped\n"
        "  stencil test: skipped\n"
        "  depth test: pass if z <= Z_d; no depth write (mask)\n"
        "  colour: RGBA = max(0, RGBA_d - RGBA_s)\n"
        "  destination colour read: yes\n"
        "  rounding: exact, clamp to [0,1], round half up to 8 bits; dither: identity\n");
  // Nothing to do.
  s = FragmentOpsState{};
  s.alpha = {true, gl::NEVER, 0};
  CHECK(contains(text_of(s), "skipped: no fragment can change the framebuffer"));
}

namespace {

// Random state; `on` forces the enables: bit 0 scissor, 1 alpha, 2 stencil,
// 3 depth, 4 blend, 5 logic op, 6 dither.
FragmentOpsState random_state(std::mt19937& rng, unsigned on, const FragmentTarget& t) {
  auto pick = [&](auto const& arr) { return arr[std::uniform_int_distribution<std::size_t>(0, std::size(arr) - 1)(rng)]; };
  auto coin = [&]() { return (rng() & 1) != 0; };
  auto unit = [&]() {
    const double choices[] = {0.0, 1.0, 0.5, -0.25, 1.5, std::uniform_real_distribution<double>(0, 1)(rng),
                              static_cast<double>(rng() % 256) / 255.0};
    return pick(choices);
  };
  FragmentOpsState s;
  std::uniform_int_distribution<int> sx(-3, t.width + 2), sy(-2, t.height + 1), sz(0, t.width + 3);
  s.scissor = {(on & 1) != 0, sx(rng), sy(rng), sz(rng), sz(rng)};
  s.alpha = {(on & 2) != 0, pick(kFuncs), unit()};
  const std::int32_t refs[] = {0, 1, 2, 3, 7, 255, 300, -4, static_cast<std::int32_t>(rng() % 256)};
  const std::uint32_t masks[] = {0xFFFFFFFFu, 0xFF, 0x0F, 0x3, 0, static_cast<std::uint32_t>(rng())};
  s.stencil = {(on & 4) != 0, pick(kFuncs), pick(refs), pick(masks), pick(kOps), pick(kOps), pick(kOps)};
  s.depth = {(on & 8) != 0, pick(kFuncs)};
  s.blend = {(on & 16) != 0, pick(kSrc), pick(kDst), pick(kEqs), {unit(), unit(), unit(), unit()}};
  s.logic = {(on & 32) != 0, static_cast<GLenum>(gl::CLEAR + rng() % 16)};
  s.dither = (on & 64) != 0;
  s.color_mask = {coin(), coin(), coin(), coin()};
  s.stencil_writemask = pick(masks);
  s.depth_mask = coin();
  return s;
}

// Buffers and spans drawn from small value sets so that equal comparisons,
// saturation and both clamps happen often.
void randomize(std::mt19937& rng, Buffers& b) {
  const std::uint32_t M = (1u << b.t.color_bits) - 1;
  auto code = [&]() {
    const std::uint32_t c[] = {0, M, M / 2, M / 2 + 1, 1, static_cast<std::uint32_t>(rng() % (M + 1))};
    return c[rng() % 6];
  };
  auto value = [&]() {
    const double v[] = {0.0, 1.0, 0.5, 0.25, std::uniform_real_distribution<double>(0, 1)(rng)};
    const double x = v[rng() % 5];
    return b.t.arith == Arithmetic::Float32 ? static_cast<double>(static_cast<float>(x)) : x;
  };
  for (auto& c : b.codes) c = static_cast<std::uint16_t>(code());
  for (auto& v : b.values) v = value();
  for (auto& s : b.stencil) {
    const std::uint32_t smax = (1u << b.t.stencil_bits) - 1;
    const std::uint32_t c[] = {0, 1, 2, 3, smax, static_cast<std::uint32_t>(rng()) & smax};
    s = static_cast<std::uint8_t>(c[rng() % 6] & smax);
  }
  for (auto& z : b.depth) {
    const std::uint32_t zmax = (b.t.depth_bits == 32) ? 0xFFFFFFFFu : (1u << b.t.depth_bits) - 1;
    const std::uint32_t c[] = {0, 5, 6, zmax, static_cast<std::uint32_t>(rng()) & zmax};
    z = c[rng() % 5];
  }
}

FragmentSpan random_span(std::mt19937& rng, const Buffers& like) {
  FragmentSpan sp;
  // Mostly inside the window; sometimes a row above or below it.
  sp.y = rng() % 8 == 0 ? (rng() % 2 ? -1 : like.t.height) : static_cast<int>(rng() % like.t.height);
  sp.x0 = static_cast<int>(rng() % (like.t.width + 6)) - 4;
  sp.count = static_cast<int>(rng() % (like.t.width + 4));
  Buffers tmp(like.t);
  tmp.codes.assign(4 * static_cast<std::size_t>(sp.count), 0);
  tmp.values.assign(like.t.arith == Arithmetic::Fixed ? 0 : 4 * static_cast<std::size_t>(sp.count), 0.0);
  tmp.stencil.clear();
  tmp.depth.assign(static_cast<std::size_t>(sp.count), 0);
  tmp.t.depth_bits = like.t.depth_bits ? like.t.depth_bits : 24;
  randomize(rng, tmp);
  if (like.t.arith == Arithmetic::Fixed) sp.codes = tmp.codes;
  else sp.values = tmp.values;
  sp.depth = tmp.depth;
  return sp;
}

const FragmentTarget kTargets[] = {
    {16, 3, Arithmetic::Fixed, 8, 8, 24},   {16, 3, Arithmetic::Fixed, 4, 3, 16},
    {16, 3, Arithmetic::Fixed, 10, 0, 0},   {16, 3, Arithmetic::Fixed, 16, 8, 24},
    {16, 3, Arithmetic::Float32, 8, 8, 24}, {16, 3, Arithmetic::Float64, 8, 1, 16},
};

void check_equivalent(const FragmentOpsState& s, const Buffers& b, const FragmentSpan& sp, unsigned on) {
  Buffers p = b, f = b;
  run_plan(s, p, sp);
  run_full(s, f, sp);
  if (!p.same(f)) {
    const FragmentPlan plan = plan_of(s, b.t);
    FAIL("plan and full path differ; enables " << on << ", arith " << static_cast<int>(b.t.arith) << " bits "
                                              << b.t.color_bits << "\n" << describe(plan, fragment_constants(s, b.t)));
  }
}

}  // namespace

TEST_CASE("plan vs full path: every stage combination, every colour mask, every target") {
  // 2^7 enable combinations x 16 colour masks x 2 depth masks x 6 targets, with random
  // parameters, buffers and spans for each (fixed seed).
  std::mt19937 rng(4242);
  long runs = 0;
  for (const FragmentTarget& t : kTargets)
    for (unsigned on = 0; on < 128; ++on)
      for (unsigned cm = 0; cm < 16; ++cm)
        for (int dm = 0; dm < 2; ++dm) {
          FragmentOpsState s = random_state(rng, on, t);
          s.color_mask = {(cm & 1) != 0, (cm & 2) != 0, (cm & 4) != 0, (cm & 8) != 0};
          s.depth_mask = dm != 0;
          Buffers b(t);
          randomize(rng, b);
          check_equivalent(s, b, random_span(rng, b), on);
          ++runs;
        }
  CHECK(runs == 6 * 128 * 16 * 2);
}

TEST_CASE("plan vs full path: many random states including every blend factor pair and equation") {
  std::mt19937 rng(99);
  for (const FragmentTarget& t : kTargets) {
    for (GLenum eq : kEqs)
      for (GLenum sf : kSrc)
        for (GLenum df : kDst) {
          FragmentOpsState s = random_state(rng, static_cast<unsigned>(rng() % 128) | 16u, t);
          s.logic.enabled = false;
          s.blend.src = sf;
          s.blend.dst = df;
          s.blend.equation = eq;
          Buffers b(t);
          randomize(rng, b);
          check_equivalent(s, b, random_span(rng, b), 16);
        }
    for (int trial = 0; trial < 3000; ++trial) {
      const unsigned on = static_cast<unsigned>(rng() % 128);
      const FragmentOpsState s = random_state(rng, on, t);
      Buffers b(t);
      randomize(rng, b);
      // Several spans in sequence: later spans see earlier writes.
      for (int k = 0; k < 3; ++k) {
        const FragmentSpan sp = random_span(rng, b);
        check_equivalent(s, b, sp, on);
        run_full(s, b, sp);
      }
    }
  }
}

TEST_CASE("plan vs full path: the equivalence test detects a wrong plan") {
  // Guard against a comparison that cannot fail: a plan built for a different state
  // (blend ADD instead of SUBTRACT) must give a different buffer on the same input.
  FragmentOpsState s;
  s.blend = {true, gl::ONE, gl::ONE, gl::FUNC_SUBTRACT, {}};
  FragmentOpsState wrong = s;
  wrong.blend.equation = gl::FUNC_ADD;
  Buffers b(kT8), p(kT8), f(kT8);
  for (auto& c : b.codes) c = 100;
  p = b;
  f = b;
  const FragmentSpan sp = span_codes(0, 0, {{150, 150, 150, 150}});
  run_fragment_plan(plan_of(wrong), fragment_constants(s, kT8), sp, p.view(), kT8.width);
  run_full(s, f, sp);
  CHECK(!p.same(f));
  CHECK(p.code(0, 0, 0) == 250);
  CHECK(f.code(0, 0, 0) == 50);
}

TEST_CASE("plan vs full path: blend (ONE, ONE) add, subtract and reverse subtract on every pair of 8-bit codes") {
  // The planned path computes these as min(s + d, M), max(s − d, 0) and
  // max(d − s, 0) (fragment_plan.cpp); the full path evaluates blend_code's
  // rnd(clamp01((s·M ± d·M) / M²)·M). Every (s, d) pair in every channel, and
  // 12- and 16-bit targets (colour maximum not known at compile time; 16 bits:
  // sums above 65535) on a sample; with all channels written (the unmasked
  // loop) and with alpha masked off (the per-pixel masked form).
  for (const bool alpha_written : {true, false})
  for (const GLenum eq : {gl::FUNC_ADD, gl::FUNC_SUBTRACT, gl::FUNC_REVERSE_SUBTRACT}) {
    FragmentOpsState s;
    s.blend = {true, gl::ONE, gl::ONE, eq, {}};
    s.color_mask = {true, true, true, alpha_written};
    Buffers b(target8(256, 256, 0, 0));
    for (int y = 0; y < 256; ++y)
      for (int x = 0; x < 256; ++x)
        for (int c = 0; c < 4; ++c) b.codes[4 * b.px(x, y) + c] = static_cast<std::uint16_t>(c % 2 ? 255 - x : x);
    for (int y = 0; y < 256; ++y) {
      std::vector<std::array<std::uint16_t, 4>> src(256);
      for (auto& k : src) k = {static_cast<std::uint16_t>(y), static_cast<std::uint16_t>(255 - y), static_cast<std::uint16_t>(y), static_cast<std::uint16_t>(255 - y)};
      b = run_both(s, b, span_codes(y, 0, src));
    }
    // Spot values: s = y, d = x on channel 0.
    const auto expect = [&](int sv, int dv) {
      return eq == gl::FUNC_ADD ? std::min(sv + dv, 255) : eq == gl::FUNC_SUBTRACT ? std::max(sv - dv, 0) : std::max(dv - sv, 0);
    };
    for (const auto& [x, y] : {std::pair{0, 0}, {200, 100}, {100, 200}, {255, 255}, {17, 254}})
      CHECK(b.code(x, y, 0) == expect(y, x));
    for (const int bits : {12, 16}) {
      Buffers w({64, 4, Arithmetic::Fixed, bits, 0, 0});
      std::mt19937 rng(static_cast<unsigned>(eq) + static_cast<unsigned>(bits));
      const std::uint32_t M = (1u << bits) - 1;
      auto code = [&] { return static_cast<std::uint16_t>(rng() % 4 == 0 ? M - rng() % 3 : rng() % (M + 1)); };
      for (auto& k : w.codes) k = code();
      for (int y = 0; y < 4; ++y) {
        std::vector<std::array<std::uint16_t, 4>> src(64);
        for (auto& k : src)
          for (auto& v : k) v = code();
        w = run_both(s, w, span_codes(y, 0, src));
      }
    }
  }
}

namespace {

// The fragments of one primitive at distinct pixels of the write rectangle, in a
// random order, with random colours and depths; through run_fragment_plan_pixels
// on `p`, and through the full path one fragment at a time on `f`.
bool pixels_match_full(std::mt19937& rng, const FragmentOpsState& s, Buffers& p, Buffers& f, bool plant) {
  const FragmentTarget& t = p.t;
  const FragmentConstants k = fragment_constants(s, t);
  std::vector<std::uint32_t> pixel;
  for (int y = k.rect.y0; y < k.rect.y1; ++y)
    for (int x = k.rect.x0; x < k.rect.x1; ++x)
      if (rng() % 4 != 0) pixel.push_back(static_cast<std::uint32_t>(y * t.width + x));
  std::shuffle(pixel.begin(), pixel.end(), rng);
  FragmentTarget ft = t;  // one colour and one depth per window pixel, random
  ft.depth_bits = t.depth_bits ? t.depth_bits : 24;
  Buffers all(ft);
  randomize(rng, all);
  const int n = static_cast<int>(pixel.size());
  run_fragment_plan_pixels(plan_of(s, t), k, all.codes.data(), all.depth.data(), pixel.data(), n, p.view());
  for (int i = 0; i < n; ++i) {
    const auto q = static_cast<int>(pixel[static_cast<std::size_t>(i)]);
    const auto o = 4 * static_cast<std::size_t>(i);
    FragmentSpan one = span_codes(q / t.width, q % t.width + (plant && i == 0 ? 1 : 0),
                                  {{all.codes[o], all.codes[o + 1], all.codes[o + 2], all.codes[o + 3]}},
                                  {all.depth[static_cast<std::size_t>(i)]});
    run_full(s, f, one);
  }
  return p.same(f);
}

}  // namespace

TEST_CASE("plan vs full path: fragments listed by pixel (run_fragment_plan_pixels), random states, over several chunks") {
  // The span path's triangle groups: fragments of one triangle from several rows,
  // one call. Distinct pixels, so any order gives the full path's buffers. A
  // 40 x 20 window (up to 800 fragments: several 256-fragment chunks), the fixed
  // targets, every combination of enables (scissor, alpha, stencil, depth, blend,
  // logic op, dither) with random parameters.
  std::mt19937 rng(777);
  int compared = 0;
  for (const FragmentTarget& t0 : kTargets) {
    if (t0.arith != Arithmetic::Fixed) continue;
    FragmentTarget t = t0;
    t.width = 40;
    t.height = 20;
    for (unsigned on = 0; on < 128; ++on) {
      const FragmentOpsState s = random_state(rng, on, t);
      Buffers b(t);
      randomize(rng, b);
      Buffers p = b, f = b;
      INFO("enables ", on, " bits ", t.color_bits);
      REQUIRE(pixels_match_full(rng, s, p, f, false));
      ++compared;
    }
  }
  CHECK(compared == 4 * 128);
}

TEST_CASE("plan vs full path: listed pixels, the depth test alone, every function and mask, 16-, 24- and 32-bit depth") {
  // The depth-only stage on listed pixels (eight fragments at a time where the
  // machine has AVX2): every comparison with and without depth writes, fragments
  // killed before it by the alpha test or not, depths from small sets (equal
  // values often) and, on the 32-bit target, above 2^31 (unsigned comparisons).
  std::mt19937 rng(778);
  int compared = 0;
  for (const int depth_bits : {16, 24, 32}) {
    const FragmentTarget t{40, 20, Arithmetic::Fixed, 8, 0, depth_bits};
    for (const GLenum func : kFuncs)
      for (const bool mask : {false, true})
        for (const bool alpha : {false, true})
          for (int rep = 0; rep < 4; ++rep) {
            FragmentOpsState s = random_state(rng, alpha ? 8u | 2u : 8u, t);
            s.depth.func = func;
            s.depth_mask = mask;
            Buffers b(t);
            randomize(rng, b);
            Buffers p = b, f = b;
            INFO("func ", func, " mask ", mask, " alpha ", alpha, " depth bits ", depth_bits);
            REQUIRE(pixels_match_full(rng, s, p, f, false));
            ++compared;
          }
  }
  CHECK(compared == 3 * 8 * 2 * 2 * 4);
}

TEST_CASE("plan vs full path: the alpha test on long spans and listed pixels, every function, every 8-bit code, 16-bit codes") {
  // The alpha test eight fragments at a time (fragment_plan.cpp alpha_test_fixed8,
  // where the machine has AVX2) and its scalar tail: spans of 0 to 300 fragments
  // holding every alpha code (8-bit target) or codes around the reference and the
  // ends of the range (16-bit target), each function, several references.
  std::mt19937 rng(2718);
  int compared = 0;
  for (const int bits : {8, 16}) {
    const FragmentTarget t{320, 2, Arithmetic::Fixed, bits, 0, 0};
    const std::uint32_t M = (1u << bits) - 1;
    for (const GLenum func : kFuncs)
      for (const double ref : {0.0, 1.0, 0.5, 77.0 / 255.0, 0.9999}) {
        FragmentOpsState s;
        s.alpha = {true, func, ref};
        const std::uint32_t rc = alpha_ref_code(ref, bits);
        for (const int count : {0, 7, 8, 9, 31, 256, 257, 300}) {
          std::vector<std::array<std::uint16_t, 4>> frags;
          for (int i = 0; i < count; ++i) {
            const std::uint32_t near[] = {0, M, rc, rc + 1, rc - 1, static_cast<std::uint32_t>(i)};
            const std::uint32_t a = bits == 8 ? static_cast<std::uint32_t>(i) & M : near[rng() % 6] & M;
            frags.push_back({static_cast<std::uint16_t>(rng() & M), static_cast<std::uint16_t>(i & M),
                             static_cast<std::uint16_t>(rng() & M), static_cast<std::uint16_t>(a)});
          }
          Buffers b(t);
          randomize(rng, b);
          INFO("bits ", bits, " func ", func, " ref ", ref, " count ", count);
          run_both(s, b, span_codes(1, static_cast<int>(rng() % 8), frags));
          Buffers p = b, f = b;
          REQUIRE(pixels_match_full(rng, s, p, f, false));
          ++compared;
        }
      }
  }
  CHECK(compared == 2 * 8 * 5 * 8);
}

TEST_CASE("plan vs full path: the stencil test without depth on long rows, uniform and mixed 32-pixel blocks") {
  // The stencil stage on a row without the depth test (fragment_plan.cpp: a block
  // of 32 equal stored values takes the tables' entries at once, where the
  // machine has AVX2; other blocks go fragment by fragment): every function,
  // every sfail and dppass operation, 8 and 3 stencil bits, the alpha test before
  // it or not, the scissor box or not. The stored row is runs of equal values
  // (most of them 32 or more long) so that both kinds of block occur; the test
  // counts the blocks that are uniform.
  std::mt19937 rng(31415);
  long uniform_blocks = 0, mixed_blocks = 0;
  int compared = 0;
  for (const int sbits : {8, 3}) {
    const FragmentTarget t{300, 3, Arithmetic::Fixed, 8, sbits, sbits == 8 ? 0 : 24};
    const std::uint32_t smax = (1u << sbits) - 1;
    for (const GLenum func : kFuncs)
      for (const GLenum sfail : kOps)
        for (const GLenum dppass : kOps) {
          FragmentOpsState s = random_state(rng, 4u | (rng() % 2 ? 2u : 0u) | (rng() % 4 == 0 ? 1u : 0u), t);
          s.stencil.func = func;
          s.stencil.sfail = sfail;
          s.stencil.dppass = dppass;
          s.depth.enabled = false;
          if (rng() % 2) s.stencil_writemask = 0xFF;
          Buffers b(t);
          randomize(rng, b);
          for (int y = 0; y < t.height; ++y)
            for (int x = 0; x < t.width;) {
              const std::uint32_t vals[] = {0, 1, 2, smax, static_cast<std::uint32_t>(rng()) & smax};
              const auto v = static_cast<std::uint8_t>(vals[rng() % 5]);
              const int len = rng() % 4 == 0 ? 1 + static_cast<int>(rng() % 8) : 32 + static_cast<int>(rng() % 90);
              for (int i = 0; i < len && x < t.width; ++i, ++x) b.stencil[b.px(x, y)] = v;
            }
          FragmentSpan sp = random_span(rng, b);
          sp.y = static_cast<int>(rng() % t.height);
          sp.x0 = static_cast<int>(rng() % 9) - 4;
          sp.count = 200 + static_cast<int>(rng() % 110);
          sp.codes.resize(4 * static_cast<std::size_t>(sp.count));
          for (std::size_t i = 0; i < sp.codes.size(); ++i) sp.codes[i] = static_cast<std::uint16_t>(rng() % 3 ? 0 : rng() & 255);
          sp.depth.assign(static_cast<std::size_t>(sp.count), 0);
          // The blocks as the planned path cuts them (chunks of 256 from the
          // first fragment inside the write rectangle, blocks of 32 from each
          // chunk's start).
          const FragmentConstants k = fragment_constants(s, t);
          const int begin = std::max(sp.x0, k.rect.x0), end = std::min(sp.x0 + sp.count, k.rect.x1);
          if (sp.y >= k.rect.y0 && sp.y < k.rect.y1)
            for (int c = begin; c < end; c += 256)
              for (int x = c; x + 32 <= std::min(c + 256, end); x += 32) {
                bool same = true;
                for (int i = 1; i < 32; ++i) same &= b.stencil[b.px(x + i, sp.y)] == b.stencil[b.px(x, sp.y)];
                ++(same ? uniform_blocks : mixed_blocks);
              }
          INFO("stencil bits ", sbits, " func ", func, " sfail ", sfail, " dppass ", dppass);
          run_both(s, b, sp);
          ++compared;
        }
  }
  MESSAGE("uniform blocks " << uniform_blocks << ", mixed blocks " << mixed_blocks);
  CHECK(compared == 2 * 8 * 8 * 8);
  CHECK(uniform_blocks > 2000);
  CHECK(mixed_blocks > 1000);
}

TEST_CASE("listed pixels: the depth test's comparisons recorded, and reused without the depth buffer (ListedDepthTest)") {
  // run_fragment_plan_pixels records each fragment's z OP stored (alive or not),
  // whether a fragment passing it has z != stored, and whether a depth changed:
  // checked against the comparisons computed here from the buffer before the
  // call, every function, with and without depth writes, the alpha test and the
  // stencil test (which records nothing when it writes, and is a mask before the
  // recorded comparisons when its three operations are KEEP), fragment counts
  // with chunk tails. Given
  // the comparisons as known (when nothing would be stored), the same call leaves
  // the colour and stencil as without them and neither reads nor writes the
  // depth buffer (a poisoned one stays as it was, and changes nothing).
  std::mt19937 rng(779);
  const FragmentTarget t{40, 20, Arithmetic::Fixed, 8, 8, 24};
  int recorded = 0, would_store = 0, reused = 0, reused_under_stencil = 0;
  for (const GLenum func : kFuncs)
    for (const bool mask : {false, true})
      for (const bool alpha : {false, true})
        for (const int stencil : {0, 1, 2})  // none, random operations, all three KEEP
          for (int rep = 0; rep < 6; ++rep) {
            INFO("func ", func, " mask ", mask, " alpha ", alpha, " stencil ", stencil, " rep ", rep);
            FragmentOpsState s = random_state(rng, 8u | (alpha ? 2u : 0u) | (stencil ? 4u : 0u), t);
            s.depth.func = func;
            s.depth_mask = mask;
            if (stencil == 2) s.stencil.sfail = s.stencil.dpfail = s.stencil.dppass = gl::KEEP;
            const FragmentPlan plan = plan_of(s, t);
            const FragmentConstants k = fragment_constants(s, t);
            std::vector<std::uint32_t> pixel(static_cast<std::size_t>(t.width * t.height));
            for (std::size_t i = 0; i < pixel.size(); ++i) pixel[i] = static_cast<std::uint32_t>(i);
            std::shuffle(pixel.begin(), pixel.end(), rng);
            pixel.resize(1 + rng() % (rep % 2 ? 12 : pixel.size()));  // (a few: all in the 8-wide loop's tail)
            const int n = static_cast<int>(pixel.size());
            Buffers before(t), frags({n, 1, Arithmetic::Fixed, 8, 0, 24});
            randomize(rng, before);
            randomize(rng, frags);  // (colours and depths from small sets: equal depths often)
            Buffers plain = before, rec = before;
            run_fragment_plan_pixels(plan, k, frags.codes.data(), frags.depth.data(), pixel.data(), n, plain.view());
            std::vector<std::uint8_t> cmp(static_cast<std::size_t>(n), 7);
            ListedDepthTest dt;
            dt.record = cmp.data();
            run_fragment_plan_pixels(plan, k, frags.codes.data(), frags.depth.data(), pixel.data(), n, rec.view(), &dt);
            REQUIRE(rec.same(plain));
            if (stencil == 2) {  // (the stencil mask then the depth test: as the full path)
              Buffers p = before, f = before;
              REQUIRE(pixels_match_full(rng, s, p, f, false));
            }
            // (the depth test with no stencil test, or one whose operations are all KEEP)
            const bool depth_alone = depth_test_alone(plan.key) && !plan.key.nothing;
            if (stencil == 2) CHECK(depth_alone == plan.key.depth);
            CHECK(dt.recorded == depth_alone);
            const bool changed = plain.depth != before.depth;
            if (!depth_alone) {
              CHECK((!changed || dt.stored));  // (conservative with the stencil test)
              continue;
            }
            bool would = false;
            for (int i = 0; i < n; ++i) {
              const std::uint32_t z = frags.depth[static_cast<std::size_t>(i)], zb = before.depth[pixel[static_cast<std::size_t>(i)]];
              const bool expect = test_func<std::uint32_t>(func, z, zb);
              REQUIRE(cmp[static_cast<std::size_t>(i)] == (expect ? 1 : 0));
              would |= expect && z != zb;
            }
            CHECK(dt.would_store == would);
            CHECK(dt.stored == changed);
            ++recorded;
            would_store += would;
            if (would && plan.key.depth_write) continue;  // (the caller may not reuse them)
            Buffers known = before;
            for (std::uint32_t& z : known.depth) z = static_cast<std::uint32_t>(rng()) & 0xFFFFFFu;
            const std::vector<std::uint32_t> poison = known.depth;
            ListedDepthTest kd;
            kd.known = cmp.data();
            run_fragment_plan_pixels(plan, k, frags.codes.data(), frags.depth.data(), pixel.data(), n, known.view(), &kd);
            CHECK(known.codes == plain.codes);
            CHECK(known.stencil == plain.stencil);
            CHECK(known.depth == poison);
            CHECK_FALSE(kd.stored);
            CHECK_FALSE(kd.recorded);
            ++reused;
            reused_under_stencil += plan.key.stencil;
          }
  MESSAGE("recorded " << recorded << ", would store " << would_store << ", reused " << reused << " (under a stencil test "
                      << reused_under_stencil << ")");
  CHECK(recorded > 150);
  CHECK(would_store > 150);
  CHECK(reused > 75);
  CHECK(reused_under_stencil > 25);
  // run_fragment_plan on row spans reports a changed depth exactly for the depth
  // test alone, and whenever one changed otherwise.
  const FragmentTarget r{16, 3, Arithmetic::Fixed, 8, 8, 24};
  int spans = 0;
  for (unsigned on = 0; on < 128; ++on)
    for (int rep = 0; rep < 8; ++rep) {
      const FragmentOpsState s = random_state(rng, on | 8u, r);  // (the depth test on)
      Buffers b(r);
      randomize(rng, b);
      Buffers after = b;
      const FragmentSpan sp = random_span(rng, b);
      const FragmentPlan plan = plan_of(s, r);
      const bool reported = run_fragment_plan(plan, fragment_constants(s, r), sp, after.view(), r.width);
      const bool changed = after.depth != b.depth;
      INFO("enables ", on, " rep ", rep);
      if (plan.key.depth && !plan.key.stencil) CHECK(reported == changed);
      else CHECK((!changed || reported));
      spans += changed;
    }
  MESSAGE("spans whose depth changed: " << spans);
  CHECK(spans > 50);
}

TEST_CASE("plan vs full path: the pixel-list comparison detects a misplaced fragment, and bad calls are refused") {
  std::mt19937 rng(778);
  FragmentOpsState s;  // a plain copy: a fragment one pixel off leaves a visible difference
  const FragmentTarget t = target8(40, 20);
  Buffers b(t);
  Buffers p = b, f = b;
  CHECK_FALSE(pixels_match_full(rng, s, p, f, true));
  const std::uint16_t codes[4] = {1, 2, 3, 4};
  const std::uint32_t pixel[1] = {0};
  s.depth = {true, gl::LESS};
  CHECK_THROWS_AS(run_fragment_plan_pixels(plan_of(s, t), fragment_constants(s, t), codes, nullptr, pixel, 1, b.view()),
                  std::invalid_argument);
  const FragmentTarget tf{40, 20, Arithmetic::Float32, 8, 8, 24};
  Buffers bf(tf);
  CHECK_THROWS_AS(run_fragment_plan_pixels(plan_of(FragmentOpsState{}, tf), fragment_constants(FragmentOpsState{}, tf), codes,
                                           nullptr, pixel, 1, bf.view()),
                  std::invalid_argument);
}

TEST_CASE("plan vs full path: one written channel, every blend factor pair and equation") {
  // The colour stage's one-channel kernel (fragment_plan.cpp color_stage_fixed):
  // each channel alone, every factor pair and equation, on spans and on listed
  // pixels (the alpha-only passes of the paper are of this kind).
  std::mt19937 rng(5150);
  int compared = 0;
  for (const FragmentTarget& t0 : kTargets) {
    if (t0.arith != Arithmetic::Fixed) continue;
    FragmentTarget t = t0;
    t.width = 24;
    t.height = 12;
    for (int c = 0; c < 4; ++c)
      for (GLenum eq : kEqs)
        for (GLenum sf : kSrc)
          for (GLenum df : kDst) {
            FragmentOpsState s = random_state(rng, static_cast<unsigned>(rng() % 128) | 16u, t);
            s.logic.enabled = false;
            s.blend = {true, sf, df, eq, s.blend.color};
            s.color_mask = {c == 0, c == 1, c == 2, c == 3};
            Buffers b(t);
            randomize(rng, b);
            check_equivalent(s, b, random_span(rng, b), 16);
            Buffers p = b, f = b;
            INFO("channel ", c, " eq ", eq, " src ", sf, " dst ", df);
            REQUIRE(pixels_match_full(rng, s, p, f, false));
            ++compared;
          }
  }
  CHECK(compared > 4 * 4 * 5 * 10 * 10);
}
