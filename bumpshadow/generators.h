// Procedural height fields, all deterministic from their parameters (and seed),
// and a registry so command lines and traces can call them by name with
// key=value parameters. docs/bumpshadow.md §2 lists every generator.
#pragma once
#include <map>
#include <string>
#include <vector>

#include "bumpshadow/heightfield.h"

namespace ffsim::bumpshadow {

// A single hemisphere of radius r centred on texel (cx, cy) over flat ground:
// z = sqrt(r^2 - d^2) for d < r, else 0.
HeightField hemisphere_bump(int width, int height, double radius, Border border = Border::Clamp);
HeightField hemisphere_bump(int width, int height, double radius, double cx, double cy, Border border);

using GeneratorParams = std::map<std::string, std::string>;

struct GeneratorParamInfo {
  std::string key, default_value, meaning;
};
struct GeneratorInfo {
  std::string name, summary;
  std::vector<GeneratorParamInfo> params;  // all keys accepted, with defaults
};

// Every registered generator: bump, bumps, ridges, craters, fractal.
const std::vector<GeneratorInfo>& generators();

// Generates by name. Unknown names, unknown keys, unparsable or out-of-range
// values throw HeightFieldError naming the generator, key and accepted values.
HeightField generate(const std::string& name, const GeneratorParams& params = {});

// "name k=v k=v" with every key (defaults filled in), sorted: a canonical
// description for reports and cache keys.
std::string describe_generator(const std::string& name, const GeneratorParams& params);

// Parses "k=v" strings into params (error on a missing '=').
GeneratorParams parse_generator_params(const std::vector<std::string>& kv);

}  // namespace ffsim::bumpshadow
