#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>
#include <unistd.h>

#include "bumpshadow/cache.h"
#include "bumpshadow/generators.h"

using namespace ffsim::bumpshadow;
namespace fs = std::filesystem;

namespace {
fs::path fresh_dir(const char* name) {
  const fs::path d = fs::temp_directory_path() / ("ffsim_bumpshadow_" + std::string(name) + "_" +
                                                  std::to_string(static_cast<long long>(::getpid())));
  fs::remove_all(d);
  return d;
}
}  // namespace

TEST_CASE("cache: a second run is read back, a changed parameter recomputes") {
  const fs::path dir = fresh_dir("cache");
  const HeightField hf = generate("fractal", {{"w", "16"}});
  ShadowMapOptions o;
  o.rays = rays_for_count(36);
  o.threads = 1;
  bool hit = true;
  const EllipseMap a = cached_ellipse_map(hf, o, dir.string(), &hit);
  CHECK_FALSE(hit);
  const EllipseMap b = cached_ellipse_map(hf, o, dir.string(), &hit);
  CHECK(hit);
  CHECK(a == b);
  CHECK(a == compute_ellipse_map(hf, o));
  o.threads = 2;  // not part of the key
  cached_ellipse_map(hf, o, dir.string(), &hit);
  CHECK(hit);
  o.fit.shadow_weight = 2;  // a result-changing option
  cached_ellipse_map(hf, o, dir.string(), &hit);
  CHECK_FALSE(hit);
  o.fit.shadow_weight = 1;
  cached_ellipse_map(hf.scaled(1.5), o, dir.string(), &hit);  // another height field
  CHECK_FALSE(hit);
  // A truncated file is recomputed and rewritten.
  int files = 0;
  for (const auto& f : fs::directory_iterator(dir)) {
    ++files;
    fs::resize_file(f.path(), 20);
  }
  CHECK(files == 3);
  const EllipseMap c = cached_ellipse_map(hf, o, dir.string(), &hit);
  CHECK_FALSE(hit);
  CHECK(c == a);
  cached_ellipse_map(hf, o, dir.string(), &hit);
  CHECK(hit);

  const HorizonMap h1 = cached_horizon_map(hf, 8, {}, dir.string(), 1, {}, &hit);
  CHECK_FALSE(hit);
  const HorizonMap h2 = cached_horizon_map(hf, 8, {}, dir.string(), 1, {}, &hit);
  CHECK(hit);
  CHECK(h1.elevation == h2.elevation);
  cached_horizon_map(hf, 16, {}, dir.string(), 1, {}, &hit);
  CHECK_FALSE(hit);
  fs::remove_all(dir);
}
