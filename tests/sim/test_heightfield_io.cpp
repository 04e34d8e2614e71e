#include <doctest/doctest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>

#include "sim/cli/cli.h"
#include "sim/heightfield_io.h"

using namespace ffsim;
namespace fs = std::filesystem;

namespace {
fs::path fresh_dir(const char* name) {
  const fs::path d = fs::temp_directory_path() / ("ffsim_hfio_" + std::string(name) + "_" + std::to_string(::getpid()));
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}
}  // namespace

TEST_CASE("heightfield_io: a 16-bit PNG becomes heights code / 65535 * scale, rows bottom to top") {
  const fs::path d = fresh_dir("png16");
  Image im = Image::make(3, 2, 1, SampleType::U16);
  for (int i = 0; i < 6; ++i) im.u16[i] = static_cast<std::uint16_t>(i * 13107);  // 0, 0.2, ..., 1.0
  write_image((d / "h.png").string(), im);
  const bumpshadow::HeightField hf = load_heightfield((d / "h.png").string(), 10.0, bumpshadow::Border::Clamp);
  CHECK(hf.width() == 3);
  CHECK(hf.height() == 2);
  CHECK(hf.border() == bumpshadow::Border::Clamp);
  CHECK(hf.at(0, 0) == 0.0);
  CHECK(hf.at(1, 0) == doctest::Approx(2.0));   // 13107/65535 = 0.2 exactly, times 10
  CHECK(hf.at(2, 1) == doctest::Approx(10.0));  // the last sample (x=2, y=1) is 65535
  // an 8-bit PNG and an EXR
  Image im8 = Image::make(2, 2, 3, SampleType::U8);
  im8.u8 = {255, 0, 0, 51, 9, 9, 0, 0, 0, 102, 1, 1};  // channel 0 is used
  write_image((d / "h8.png").string(), im8);
  const bumpshadow::HeightField h8 = load_heightfield((d / "h8.png").string(), 1.0, bumpshadow::Border::Wrap);
  CHECK(h8.at(0, 0) == 1.0);
  CHECK(h8.at(1, 0) == doctest::Approx(0.2));
  CHECK(h8.at(1, 1) == doctest::Approx(0.4));
  Image f = Image::make(2, 2, 1, SampleType::F32);
  f.f32 = {0.5f, 1.5f, -2.0f, 3.25f};
  write_image((d / "h.exr").string(), f);
  const bumpshadow::HeightField he = load_heightfield((d / "h.exr").string(), 2.0, bumpshadow::Border::Wrap);
  CHECK(he.at(1, 1) == 6.5);
  CHECK(he.at(0, 1) == -4.0);
  fs::remove_all(d);
}

TEST_CASE("heightfield_io: bad files and sizes give errors that name the file") {
  const fs::path d = fresh_dir("bad");
  Image one = Image::make(1, 1, 1, SampleType::U8);
  write_image((d / "one.png").string(), one);
  const std::string p = (d / "one.png").string();
  CHECK_THROWS_WITH_AS(load_heightfield(p, 1.0, bumpshadow::Border::Wrap),
                       (p + ": 1x1 image is too small for a height field (at least 2x2)").c_str(),
                       bumpshadow::HeightFieldError);
  CHECK_THROWS_AS(load_heightfield((d / "missing.png").string(), 1.0, bumpshadow::Border::Wrap), ImageError);
  std::ofstream((d / "junk.png").string()) << "not a png";
  CHECK_THROWS_AS(load_heightfield((d / "junk.png").string(), 1.0, bumpshadow::Border::Wrap), ImageError);
  CHECK_THROWS_AS(load_heightfield(p, 0.0, bumpshadow::Border::Wrap), bumpshadow::HeightFieldError);
  fs::remove_all(d);
}

TEST_CASE("heightfield_io: the bumpshadow command writes every map, a report, and uses its cache") {
  const fs::path d = fresh_dir("cli");
  auto run = [](std::vector<std::string> a, std::string* out_text = nullptr) {
    std::ostringstream out, err;
    const int code = cli::run(a, out, err);
    if (out_text) *out_text = out.str() + err.str();
    return code;
  };
  std::string text;
  const std::string o = (d / "out").string();
  REQUIRE(run({"bumpshadow", "--generate", "bumps", "w=16", "spacing=8", "r=3", "--rays", "36", "--threads", "2",
               "--out", o},
              &text) == 0);
  CHECK(text.find("cache       computed") != std::string::npos);
  for (const char* f : {"t1r.exr", "t1r.png", "t2r.exr", "t2r.png", "t3r.exr", "t3r.png", "t1n.exr", "t1n.png",
                        "t2n.exr", "t2n.png", "normal.exr", "normal.png", "heights.exr", "horizon-0.exr",
                        "horizon-1.exr", "report.txt", "report.json"})
    CHECK(fs::exists(d / "out" / f));
  const Image t1r = read_image((d / "out" / "t1r.png").string());
  CHECK(t1r.width == 16);
  CHECK(t1r.channels == 4);
  CHECK(t1r.type == SampleType::U8);
  CHECK(read_image((d / "out" / "t1n.exr").string()).type == SampleType::F32);
  REQUIRE(run({"bumpshadow", "--generate", "bumps", "w=16", "spacing=8", "r=3", "--rays", "36", "--out", o}, &text) == 0);
  CHECK(text.find("cache       hit") != std::string::npos);
  REQUIRE(run({"bumpshadow", "--generate", "bumps", "w=16", "spacing=8", "r=3", "--rays", "49", "--out", o}, &text) == 0);
  CHECK(text.find("cache       computed") != std::string::npos);  // changed parameter
  REQUIRE(run({"bumpshadow", "--generate", "bumps", "w=16", "spacing=8", "r=3", "--rays", "49", "--max-distance", "4",
               "--out", o},
              &text) == 0);
  CHECK(text.find("cache       computed") != std::string::npos);  // the march cut-off is part of the key
  CHECK(text.find("max_distance=4") != std::string::npos);
  CHECK(run({"bumpshadow", "--generate", "bumps", "--max-distance", "-1"}) == 2);
  // lights: exact reference maps and the error fractions of the ellipse test and the horizon map
  REQUIRE(run({"bumpshadow", "--generate", "bumps", "w=16", "spacing=8", "r=3", "--rays", "36", "--light",
               "0.8,0,0.6", "--light", "0,-0.5,0.5", "--out", o},
              &text) == 0);
  CHECK(text.find("light 0") != std::string::npos);
  CHECK(text.find("light 1") != std::string::npos);
  CHECK(text.find("horizon map wrong on") != std::string::npos);
  CHECK(fs::exists(d / "out" / "reference-1.png"));
  std::ifstream js((d / "out" / "report.json").string());
  const std::string json((std::istreambuf_iterator<char>(js)), std::istreambuf_iterator<char>());
  CHECK(json.find("\"ellipse_error\": ") != std::string::npos);
  CHECK(run({"bumpshadow", "--generate", "bumps", "--light", "1,0,-1"}) == 2);  // below the horizon
  CHECK(run({"bumpshadow", "--generate", "bumps", "--light", "1,0"}) == 2);
  // a file input
  Image im = Image::make(8, 8, 1, SampleType::U8);
  im.u8[27] = 255;
  write_image((d / "h.png").string(), im);
  REQUIRE(run({"bumpshadow", (d / "h.png").string(), "--scale", "4", "--rays", "16", "--no-cache", "--horizon", "0",
               "--out", (d / "f").string()},
              &text) == 0);
  CHECK(text.find("cache       off") != std::string::npos);
  CHECK_FALSE(fs::exists(d / "f" / "horizon-0.exr"));
  // usage errors
  CHECK(run({"bumpshadow"}) == 2);
  CHECK(run({"bumpshadow", "--generate", "bump", "--rays", "x"}) == 2);
  CHECK(run({"bumpshadow", "--generate", "nope", "--out", o}, &text) == 1);
  CHECK(text.find("unknown height field generator `nope`") != std::string::npos);
  CHECK(run({"bumpshadow", "--list"}, &text) == 0);
  CHECK(text.find("craters:") != std::string::npos);
  fs::remove_all(d);
}
