// The paper's trace generators (sim/trace/generators.cpp, issue 8): height fields by
// name, the shadowmap maps exactly as bumpshadow encodes them, field selection by
// index, key errors; and the committed terrain mesh includes equal their generator.
#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "bumpshadow/encodings.h"
#include "bumpshadow/generators.h"
#include "bumpshadow/reference.h"
#include "bumpshadow/shadow_map.h"
#include "sim/paper.h"
#include "sim/trace/trace.h"

using namespace ffsim;
using namespace ffsim::trace;
namespace fs = std::filesystem;

namespace {
const std::string V = "ffsim-trace 1\nframebuffer 8 8\n";

const Image& resource(const Program& p, const std::string& name) {
  for (const auto& r : p.resources)
    if (r.name == name) return *r.image;
  FAIL("no resource " << name);
  throw std::logic_error("unreachable");
}

std::string read_file(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

std::string cache_key() { return std::string("cache=") + (fs::temp_directory_path() / "ffsim-test-paper-cache").string(); }
}  // namespace

TEST_CASE("paper generators: every bumpshadow height field is a generator of the same heights") {
  const Program p = load_trace_text(V +
                                        "generate a fractal w=16 seed=3\n"
                                        "generate b bumps w=16 spacing=8 r=3 scale=2\n"
                                        "generate c craters w=16 count=4\n",
                                    "t.trace", {});
  const bumpshadow::HeightField fa = bumpshadow::generate("fractal", {{"w", "16"}, {"seed", "3"}});
  const bumpshadow::HeightField fb = bumpshadow::generate("bumps", {{"w", "16"}, {"spacing", "8"}, {"r", "3"}}).scaled(2);
  const Image& a = resource(p, "a");
  const Image& b = resource(p, "b");
  REQUIRE(a.channels == 1);
  REQUIRE(a.type == SampleType::F32);
  for (int y = 0; y < 16; ++y)
    for (int x = 0; x < 16; ++x) {
      CHECK(a.f32[a.index(x, y, 0)] == static_cast<float>(fa.at(x, y)));
      CHECK(b.f32[b.index(x, y, 0)] == static_cast<float>(fb.at(x, y)));
    }
  CHECK(resource(p, "c").width == 16);
}

TEST_CASE("paper generators: shadowmap maps are the codes of bumpshadow encode_maps") {
  const Program p = load_trace_text(V + "generate t1r shadowmap field=bumps w=16 spacing=8 r=3 rays=36 map=t1r " + cache_key() +
                                        "\n"
                                        "generate t2r shadowmap field=bumps w=16 spacing=8 r=3 rays=36 map=t2r cache=none\n"
                                        "generate t3r shadowmap field=bumps w=16 spacing=8 r=3 rays=36 map=t3r cache=none\n"
                                        "generate t1n shadowmap field=(1) w=16 spacing=8 r=3 rays=36 map=t1n cache=none\n"
                                        "generate t2n shadowmap field=bumps w=16 spacing=8 r=3 rays=36 map=t2n cache=none\n"
                                        "generate n shadowmap field=bumps w=16 spacing=8 r=3 map=normal\n"
                                        "generate ref shadowmap field=bumps w=16 spacing=8 r=3 map=reference lx=0.6 ly=0.2\n",
                                    "t.trace", {});
  const bumpshadow::HeightField hf = bumpshadow::generate("bumps", {{"w", "16"}, {"spacing", "8"}, {"r", "3"}});
  bumpshadow::ShadowMapOptions o;
  o.rays = bumpshadow::rays_for_count(36);
  const bumpshadow::EncodedMaps em = bumpshadow::encode_maps(bumpshadow::compute_ellipse_map(hf, o));
  auto same = [&](const std::string& name, const bumpshadow::ByteMap& m) {
    const Image& im = resource(p, name);
    CHECK(im.type == SampleType::U8);
    CHECK(im.channels == m.channels);
    CHECK(im.width == m.width);
    CHECK(im.u8 == m.v);
  };
  same("t1r", em.t1r8);
  same("t2r", em.t2r8);
  same("t3r", em.t3r8);
  same("t1n", em.t1n8);
  same("t2n", em.t2n8);
  same("n", bumpshadow::quantise(bumpshadow::normal_map(hf)));
  CHECK(em.t3r8.channels == 1);
  const std::vector<std::uint8_t> lit = bumpshadow::reference_lit_map(hf, {0.6, 0.2, std::sqrt(1 - 0.36 - 0.04)});
  const Image& ref = resource(p, "ref");
  long long shadowed = 0;
  for (std::size_t i = 0; i < lit.size(); ++i) {
    CHECK(ref.u8[i] == (lit[i] ? 255 : 0));
    shadowed += !lit[i];
  }
  CHECK(shadowed > 0);
}

TEST_CASE("paper generators: key and light errors name the position") {
  auto error_of = [](const std::string& line) {
    try {
      load_trace_text(V + line + "\n", "t.trace", {});
    } catch (const TraceError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  CHECK(error_of("generate a shadowmap field=bumps w=8 octaves=3 map=t1r") == "t.trace:3:38: unknown key `octaves`");
  CHECK(error_of("generate a shadowmap field=bumps w=8 map=reference lx=0.9 ly=0.9").find("inside the unit disc") !=
        std::string::npos);
  CHECK(error_of("generate a shadowmap field=7 w=8 map=normal").find("must be in [0, 4]") != std::string::npos);
  CHECK(error_of("generate a shadowmap field=bumps w=8 map=t4r").find("must be t1r, t2r") != std::string::npos);
}

TEST_CASE("paper scenes: the committed terrain meshes are what ffsim paper-mesh writes") {
  const fs::path inc = fs::path(FFSIM_SOURCE_DIR) / "traces" / "include";
  CHECK(read_file(inc / "terrain-mesh.trace") == paper::terrain_mesh_trace(false));
  CHECK(read_file(inc / "terrain-mesh-lit.trace") == paper::terrain_mesh_trace(true));
  // 31 x 31 vertices: 30 strips of 62 vertices = 1800 triangles.
  const std::string t = paper::terrain_mesh_trace(false);
  long long strips = 0, vertices = 0;
  for (std::size_t at = 0; (at = t.find("glBegin GL_TRIANGLE_STRIP", at)) != std::string::npos; ++at) ++strips;
  for (std::size_t at = 0; (at = t.find("\nglVertex3d", at)) != std::string::npos; ++at) ++vertices;
  CHECK(strips == 30);
  CHECK(vertices == 30 * 62);
  // The mesh's heights are the field's surface at the vertex's texel position.
  CHECK(paper::terrain_height(0, 0) ==
        bumpshadow::generate("fractal", {{"w", "128"}, {"seed", "7"}}).scaled(4).sample(-0.5, -0.5) / 128);
}
