#include <doctest/doctest.h>

#include "pipeline/number/profile.h"

using namespace ffsim;

TEST_CASE("profile: geforce256 is the hardware of the paper") {
  const Profile* p = find_builtin_profile("geforce256");
  REQUIRE(p);
  CHECK(p->arithmetic == Arithmetic::Fixed);
  CHECK(p->color_bits == 8);
  CHECK(p->texture_bits == 8);
  CHECK(p->stencil_bits == 8);
  CHECK(p->combiner_bits == 9);  // 8 bits plus sign
  CHECK(p->texture_units == 2);
  CHECK(p->general_combiners == 2);
}

TEST_CASE("profile: the named profiles exist and ideal is binary64") {
  for (const char* n : {"geforce256", "rgba10", "rgba12", "float32", "ideal"}) CHECK(find_builtin_profile(n));
  CHECK(find_builtin_profile("ideal")->arithmetic == Arithmetic::Float64);
  CHECK(find_builtin_profile("float32")->arithmetic == Arithmetic::Float32);
  CHECK(find_builtin_profile("rgba12")->color_bits == 12);
  CHECK(find_builtin_profile("nope") == nullptr);
}

TEST_CASE("profile: format -> parse round trip for every built-in profile") {
  for (const Profile& p : builtin_profiles()) CHECK(parse_profile(format_profile(p), "x") == p);
}

TEST_CASE("profile: file with base and overrides") {
  const Profile p = parse_profile("# twelve-bit framebuffer on a GeForce 256\nbase = geforce256\n"
                                  "name = gf12\ncolor_bits = 12\n", "gf12.profile");
  CHECK(p.name == "gf12");
  CHECK(p.color_bits == 12);
  CHECK(p.combiner_bits == 9);
}

TEST_CASE("profile: errors name the source and line") {
  auto msg = [](const char* text) {
    try {
      parse_profile(text, "p.txt");
    } catch (const ProfileError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  CHECK(msg("color_bits = 8\nbogus = 1\n") == "p.txt:2: unknown key `bogus`");
  CHECK(msg("color_bits = 17\n") == "p.txt:1: color_bits = 17 is out of range (expected 1..16)");
  CHECK(msg("color_bits = eight\n") == "p.txt:1: color_bits expects an integer, got `eight`");
  CHECK(msg("just words\n") == "p.txt:1: expected `key = value`, got `just words`");
  CHECK(msg("base = voodoo2\n") == "p.txt:1: unknown base profile `voodoo2`");
  CHECK(msg("arithmetic = decimal\n") == "p.txt:1: arithmetic must be fixed, float32 or float64, got `decimal`");
  CHECK(msg("depth_bits = 20\n") == "p.txt: depth_bits = 20 (expected 0, 16 or 24)");
}
