// Image files: write then read back identically; bad files give errors naming the file.
#include <doctest/doctest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <unistd.h>

#include "sim/image_io.h"
#include "sim/test_pattern.h"

using namespace ffsim;
namespace fs = std::filesystem;

namespace {
fs::path temp_dir() {
  const fs::path d = fs::temp_directory_path() / ("ffsim-test-" + std::to_string(::getpid()));
  // Removed when the test process ends (every test of this file shares it).
  static const struct RemoveAtExit {
    fs::path dir;
    ~RemoveAtExit() {
      std::error_code ec;
      fs::remove_all(dir, ec);
    }
  } remove_at_exit{d};
  fs::create_directories(d);
  return d;
}
std::string error_of(const std::string& path) {
  try {
    read_image(path);
  } catch (const ImageError& e) {
    return e.what();
  }
  return "no error";
}
}  // namespace

TEST_CASE("image: 8-bit PNG and float EXR round trip exactly") {
  const fs::path d = temp_dir();
  FramebufferFormat f;
  f.width = 37;  // odd sizes catch row-flip and stride mistakes
  f.height = 13;
  Framebuffer fb(f);
  fill_test_pattern(fb);
  const Image c = color_image(fb);
  write_image((d / "c.png").string(), c);
  CHECK(read_image((d / "c.png").string()) == c);

  // EXR: float color; binary32 values survive exactly ("within float exactness").
  f.color_arith = Arithmetic::Float64;
  Framebuffer ff(f);
  fill_test_pattern(ff);
  ff.values()[5] = 0.123456789;  // not a k/255 value
  const Image e = color_image(ff);
  REQUIRE(e.type == SampleType::F32);
  write_image((d / "c.exr").string(), e);
  const Image back = read_image((d / "c.exr").string());
  CHECK(back == e);
  CHECK(back.f32[5] == static_cast<float>(0.123456789));
}

TEST_CASE("image: 16-bit PNG, grey alpha and stencil images round trip") {
  const fs::path d = temp_dir();
  FramebufferFormat f;
  f.width = 9;
  f.height = 5;
  f.color_bits = 12;
  Framebuffer fb(f);
  fill_test_pattern(fb);
  const Image c = color_image(fb);
  CHECK(c.type == SampleType::U16);
  write_image((d / "c16.png").string(), c);
  CHECK(read_image((d / "c16.png").string()) == c);
  const Image a = alpha_image(fb), s = stencil_image(fb);
  CHECK(a.channels == 1);
  write_image((d / "a.png").string(), a);
  write_image((d / "s.png").string(), s);
  CHECK(read_image((d / "a.png").string()) == a);
  CHECK(read_image((d / "s.png").string()) == s);
  CHECK(s.u8[s.index(3, 2, 0)] == ((3 + 2 * 2) & 255));  // raw stencil value, rows bottom-up
}

TEST_CASE("image: errors name the file and say what is wrong") {
  const fs::path d = temp_dir();
  const std::string missing = (d / "missing.png").string();
  CHECK(error_of(missing) == missing + ": no such file");
  const std::string junk = (d / "junk.png").string();
  std::ofstream(junk) << "this is not a png";
  CHECK(error_of(junk).rfind(junk + ": cannot read as an image", 0) == 0);
  // A valid PNG cut in half.
  Image big = Image::make(64, 64, 3, SampleType::U8);
  for (std::size_t i = 0; i < big.u8.size(); ++i) big.u8[i] = static_cast<std::uint8_t>(i * 7919 % 251);
  const std::string full = (d / "full.png").string(), cut = (d / "cut.png").string();
  write_image(full, big);
  {
    std::ifstream in(full, std::ios::binary);
    std::string bytes((std::istreambuf_iterator<char>(in)), {});
    std::ofstream(cut, std::ios::binary) << bytes.substr(0, bytes.size() / 2);
  }
  CHECK(error_of(cut).rfind(cut + ": ", 0) == 0);
  // Non-finite EXR samples.
  Image nan = Image::make(3, 2, 1, SampleType::F32);
  nan.f32[nan.index(2, 1, 0)] = std::numeric_limits<float>::quiet_NaN();
  const std::string nanexr = (d / "nan.exr").string();
  write_image(nanexr, nan);
  CHECK(error_of(nanexr) == nanexr + ": non-finite sample (NaN) at pixel x=2 y=0 (top-left origin), channel 0");
  Image inf = Image::make(3, 2, 1, SampleType::F32);
  inf.f32[0] = std::numeric_limits<float>::infinity();
  write_image(nanexr, inf);
  CHECK(error_of(nanexr) == nanexr + ": non-finite sample (Inf) at pixel x=0 y=1 (top-left origin), channel 0");
  CHECK_THROWS_WITH_AS(write_image((d / "x.bmpx").string(), big),
                       ((d / "x.bmpx").string() + ": unsupported output extension `.bmpx` (expected .png, .exr, .tif)").c_str(),
                       ImageError);
  CHECK_THROWS_AS(write_image((d / "no/such/dir/x.png").string(), big), ImageError);
}
