// `ffsim bench` configuration: the variants, profiles, filters, frame sizes,
// scenes and the light sweep, and the command-line options that choose them.
#pragma once
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace ffsim::bench {

// How a variant's lit mask, shadow factor and shaded image are read.
enum class VariantKind {
  Hard,       // stencil.png (0 = lit), color.png; factor = the 0/1 mask
  AA,         // alpha.png (> 0 = lit), factor.png, color.png
  Ellipse,    // the float64 ellipse test: ellipse.png of the reference run (CPU)
  Reference,  // the exact ray cast itself (CPU)
};

struct VariantSpec {
  std::string name;   // row name
  std::string trace;  // file stem under traces/ (Ellipse, Reference: kautz-reference)
  VariantKind kind = VariantKind::Hard;
  std::vector<std::pair<std::string, std::string>> sets;
  std::string note;
};

// Every variant of issue 9, in report order.
const std::vector<VariantSpec>& all_variants();
const char* kind_name(VariantKind k);

struct Light {
  double azimuth_deg = 0, elevation_deg = 0;
  double lx() const;
  double ly() const;
  std::string label() const;  // "a30e15"
};

// The sweep: elevation 60, 30, 15, 5 degrees x azimuth 0, 30, ..., 330 degrees
// (index = elevation index * 12 + azimuth index).
std::vector<Light> light_sweep();
// n lights of the sweep in the order k * 13 mod 48 (each step one elevation and one
// azimuth further, so any prefix mixes both); n >= 48 gives the whole sweep.
std::vector<Light> light_subset(int n);

struct SceneSpec {
  int scene = 0;      // the traces' `scene` parameter
  std::string name;   // polygon | terrain
};

struct AccuracyConfig {
  std::string traces_dir = "traces";
  std::string out_dir = "docs/results";  // CSV, Markdown and SVG
  std::string name = "accuracy";         // file stem of the outputs
  std::vector<VariantSpec> variants;     // default: all_variants()
  std::vector<std::string> profiles;     // `ideal` is always run too (the vs-ideal error)
  std::vector<int> filters;              // 0 NEAREST, 1 LINEAR
  std::vector<int> sizes;                // frame side in pixels (multiples of map_res)
  std::vector<SceneSpec> scenes;
  std::vector<Light> lights;
  int repeat = 5;   // timed replays after the warm-up (at the first light)
  int threads = 1;  // executor threads per replay
  int map_res = 128;     // bump and shadow map resolution, both scenes
  int rays = 256;        // rays per texel of the ellipse fit
  std::string command_line;  // recorded in the Markdown
  bool write_files = true;
};

// The default (full) configuration, and --quick: one size (256), 3 lights,
// profiles geforce256 and ideal, LINEAR only, both scenes, 2 timed repeats.
AccuracyConfig default_config();
AccuracyConfig quick_config();

// Parses the arguments of `ffsim bench`; nullopt and a one-line message on a bad option.
std::optional<AccuracyConfig> parse_accuracy_args(const std::vector<std::string>& args, std::string& error);

std::string filter_name(int filter);

}  // namespace ffsim::bench
