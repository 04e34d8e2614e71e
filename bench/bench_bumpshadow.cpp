// Times the ellipse shadow map precomputation (visibility + fit for every texel)
// and the 8-azimuth horizon map for 256^2 and 512^2 fractal height fields at 256
// and 1024 rays per texel. Prints a table and writes
// docs/results/bumpshadow_bench.csv. Usage: bench_bumpshadow [--threads N] [--quick]
// (--quick: 64^2 and 128^2 only, for a smoke run).
#include <chrono>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <string>
#include <thread>

#include "bumpshadow/generators.h"
#include "bumpshadow/horizon.h"
#include "bumpshadow/shadow_map.h"

using namespace ffsim::bumpshadow;

int main(int argc, char** argv) {
  int threads = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  bool quick = false;
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--threads") && i + 1 < argc) threads = std::max(1, std::atoi(argv[++i]));
    else if (!std::strcmp(argv[i], "--quick")) quick = true;
    else {
      std::fprintf(stderr, "usage: bench_bumpshadow [--threads N] [--quick]\n");
      return 2;
    }
  }
  const int sizes_full[] = {256, 512}, sizes_quick[] = {64, 128};
  const int* sizes = quick ? sizes_quick : sizes_full;
  const std::string csv_path = std::string(FFSIM_SOURCE_DIR) + "/docs/results/bumpshadow_bench.csv";
  std::ofstream csv(csv_path);
  csv << "field,size,rays,threads,ellipse_seconds,us_per_texel,agreement,horizon8_seconds\n";
  std::printf("fractal terrain (height 8), %d threads\n", threads);
  std::printf("%8s %6s %14s %14s %10s %14s\n", "size", "rays", "ellipse map s", "us/texel", "agreement", "horizon8 s");
  for (int si = 0; si < 2; ++si) {
    const int n = sizes[si];
    const HeightField hf = generate("fractal", {{"w", std::to_string(n)}});
    for (int rays : {256, 1024}) {
      ShadowMapOptions o;
      o.rays = rays_for_count(rays);
      o.threads = threads;
      const auto t0 = std::chrono::steady_clock::now();
      const EllipseMap m = compute_ellipse_map(hf, o);
      const auto t1 = std::chrono::steady_clock::now();
      const HorizonMap h = compute_horizon_map(hf, 8, o.rays.march, threads);
      const auto t2 = std::chrono::steady_clock::now();
      const double es = std::chrono::duration<double>(t1 - t0).count();
      const double hs = std::chrono::duration<double>(t2 - t1).count();
      const double us = 1e6 * es / (static_cast<double>(n) * n);
      std::printf("%5dx%-4d %6d %14.3f %14.2f %10.4f %14.3f\n", n, n, m.rays_per_texel, es, us, m.agreement(), hs);
      std::fflush(stdout);
      csv << "fractal," << n << "," << m.rays_per_texel << "," << threads << "," << es << "," << us << ","
          << m.agreement() << "," << hs << "\n";
      (void)h;
    }
  }
  std::printf("wrote %s\n", csv_path.c_str());
  return 0;
}
