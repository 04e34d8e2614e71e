// Named generators of client images: `generate NAME GENERATOR key=value ...` in a
// trace calls a registered function with the key=value arguments. bumpshadow's
// precomputations plug in here (one line each in sim/trace/generators.cpp).
#pragma once
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "sim/image_io.h"
#include "sim/trace/expr.h"

namespace ffsim::trace {

// The key=value arguments of one `generate` command. Values are read on demand:
// as an expression (number/integer) or as a word. Errors name the key's position.
class GeneratorArgs {
 public:
  struct Value {
    std::string text;
    SourceLoc where;  // of the value text
    bool used = false;
  };
  GeneratorArgs(std::map<std::string, Value> values, Expression::Lookup lookup, std::string line_text,
                long long max_pixels)
      : values_(std::move(values)), lookup_(std::move(lookup)), line_(std::move(line_text)), max_pixels_(max_pixels) {}

  double number(const std::string& key, double fallback);
  long long integer(const std::string& key, long long fallback, long long min, long long max);
  // One of `allowed` (the first is the default when the key is absent).
  std::string word(const std::string& key, const std::vector<std::string>& allowed);
  // The value's text as written (a path, a name), or `fallback` when absent.
  std::string text(const std::string& key, const std::string& fallback);
  bool has(const std::string& key) const { return values_.count(key) != 0; }
  // Where the key's value stands (for messages about it); {} when absent.
  SourceLoc where(const std::string& key) const;
  const std::string& line() const { return line_; }
  long long max_pixels() const { return max_pixels_; }
  // A width x height pair within the trace's pixel limit.
  std::pair<int, int> size(const std::string& wkey, const std::string& hkey, int fallback);
  // Throws for keys no read asked for.
  void finish() const;

 private:
  std::map<std::string, Value> values_;
  Expression::Lookup lookup_;
  std::string line_;
  long long max_pixels_;
};

struct GeneratorDef {
  std::string name;
  std::string keys;         // "width height radius border=clamp|wrap" for `ffsim info` and docs
  std::string description;  // one line
  std::function<Image(GeneratorArgs&)> make;
};

class GeneratorRegistry {
 public:
  void add(GeneratorDef def) { defs_[def.name] = std::move(def); }
  const GeneratorDef* find(const std::string& name) const {
    auto it = defs_.find(name);
    return it == defs_.end() ? nullptr : &it->second;
  }
  const std::map<std::string, GeneratorDef>& all() const { return defs_; }

 private:
  std::map<std::string, GeneratorDef> defs_;
};

// All generators of this build.
const GeneratorRegistry& generators();

}  // namespace ffsim::trace
