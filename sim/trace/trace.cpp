#include "sim/trace/trace.h"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <set>
#include <sstream>

#include "pipeline/gl/enum_names.h"
#include "sim/profile_io.h"
#include "sim/trace/expr.h"
#include "sim/trace/generators.h"
#include "sim/trace/lexer.h"

namespace ffsim::trace {

namespace fs = std::filesystem;

std::string buffer_kind_name(BufferKind k) {
  switch (k) {
    case BufferKind::Color: return "color";
    case BufferKind::Alpha: return "alpha";
    case BufferKind::Stencil: return "stencil";
    case BufferKind::Depth: return "depth";
  }
  return "color";
}

int Program::pass_count() const {
  int n = 0;
  for (const auto& s : steps) n += s.is_pass() ? 1 : 0;
  return n;
}

std::vector<StepHot> hot_steps(const Program& p) {
  std::vector<StepHot> hot(p.steps.size());
  for (std::size_t k = 0; k < p.steps.size(); ++k) {
    const Step& s = p.steps[k];
    StepHot& h = hot[k];
    h.kind = s.kind;
    if (s.kind != StepKind::Call || !s.def) continue;
    h.def = s.def;
    h.packed_at = s.packed_at;
    h.vertex_data = s.def->vertex_data;
    if (p.packed_args(s)) h.packed_call = s.def->packed_call;
  }
  for (std::size_t k = hot.size(); k-- > 0;) {
    const StepHot& h = hot[k];
    bool quiet = h.packed_call && h.vertex_data && !h.def->is_pass && h.def->never_errs;
    if (h.packed_call && h.vertex_data && !h.def->is_pass && h.def->errs_on_unit) {
      const std::int64_t unit = p.packed[h.packed_at].i - static_cast<std::int64_t>(gl::TEXTURE0);
      quiet = p.packed[h.packed_at].kind == ArgKind::Enum && unit >= 0 && unit < p.profile.texture_units;
    }
    const std::uint16_t next = k + 1 < hot.size() ? hot[k + 1].quiet_run : 0;
    hot[k].quiet_run = quiet ? static_cast<std::uint16_t>(std::min<int>(next + 1, 65535)) : 0;
  }
  return hot;
}

std::pair<std::string, std::string> parse_set_argument(const std::string& arg) {
  const auto eq = arg.find('=');
  if (eq == std::string::npos || eq == 0)
    throw TraceError({"--set", 1, 1}, std::string("expected NAME=VALUE, got `") + arg + "`", arg);
  return {arg.substr(0, eq), arg.substr(eq + 1)};
}

namespace {

bool is_identifier(const std::string& s) {
  if (s.empty()) return false;
  auto start = [](char c) { return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_'; };
  if (!start(s[0])) return false;
  for (char c : s)
    if (!start(c) && !(c >= '0' && c <= '9')) return false;
  return true;
}

std::string join_or(const std::vector<std::string>& v) {
  std::string s;
  for (std::size_t k = 0; k < v.size(); ++k) s += (k ? (k + 1 == v.size() ? " or " : ", ") : "") + v[k];
  return s;
}

// The name of a bitfield bit: the core token ending in _BIT with that value.
std::string bit_name(GLenum v) {
  for (std::size_t k = 0; k < gl::kEnumNameCount; ++k) {
    const std::string_view n = gl::kEnumNames[k].name;
    if (gl::kEnumNames[k].value == v && n.size() > 4 && n.substr(n.size() - 4) == "_BIT") return std::string(n);
  }
  return gl::enum_name(v);
}

struct Line {
  std::vector<Token> tok;
  SourceLoc where;  // file, line (column 1)
  std::string text;
  SourceLoc at(std::size_t k) const { return {where.file, where.line, tok[k].column}; }
  SourceLoc end() const { return {where.file, where.line, static_cast<int>(text.size()) + 1}; }
};

class Loader {
 public:
  Loader(const LoadOptions& opt) : opt_(opt), cmds_(opt.commands ? *opt.commands : gl_commands()) {
    for (const auto& s : opt.sets) {
      if (!is_identifier(s.first)) throw TraceError({"--set", 1, 1}, std::string("bad parameter name `") + s.first + "`", s.first + "=" + s.second);
      sets_[s.first] = s.second;
    }
  }

  Program finish() {
    for (const auto& [name, value] : sets_)
      if (!used_sets_.count(name))
        throw TraceError({"--set", 1, 1}, std::string("the trace has no parameter `") + name + "`", name + "=" + value);
    freeze();
    for (Step& st : prog_.steps) {  // the scalar arguments of every call, contiguous
      if (st.kind != StepKind::Call) continue;
      st.packed_at = static_cast<std::uint32_t>(prog_.packed.size());
      for (const ArgValue& v : st.args) prog_.packed.push_back({v.kind, v.i, v.f});
    }
    prog_.hot = hot_steps(prog_);
    prog_.vertex_runs = vertex_runs(prog_, prog_.hot);
    return std::move(prog_);
  }

  void load_file(const std::string& path, const Line* from, std::size_t from_tok, int depth) {
    auto fail = [&](const std::string& m) -> TraceError {
      if (from) return TraceError(from->at(from_tok), m, from->text);
      return TraceError({}, m);
    };
    std::error_code ec;
    if (!fs::exists(path, ec)) throw fail(std::string("cannot read `") + path + "`: no such file");
    if (!fs::is_regular_file(path, ec)) throw fail(std::string("cannot read `") + path + "`: not a regular file");
    check_root(path, fail);
    const auto size = fs::file_size(path, ec);
    if (ec || size > kMaxTraceFileBytes)
      throw fail(std::string("cannot read `") + path + "`: larger than " + std::to_string(kMaxTraceFileBytes) + " bytes");
    total_bytes_ += size;
    if (total_bytes_ > kMaxTraceTotalBytes)
      throw fail(std::string("the trace reads more than ") + std::to_string(kMaxTraceTotalBytes) + " bytes (includes expanded)");
    std::ifstream in(path, std::ios::binary);
    std::stringstream ss;
    ss << in.rdbuf();
    if (!in && !in.eof()) throw fail(std::string("cannot read `") + path + "`");
    const std::string canon = fs::weakly_canonical(path, ec).string();
    for (std::size_t k = 0; k < stack_.size(); ++k)
      if (stack_[k] == canon) {
        std::string chain;
        for (std::size_t j = k; j < stack_.size(); ++j) chain += stack_names_[j] + " -> ";
        throw fail(std::string("include cycle: ") + chain + path);
      }
    load_text(ss.str(), path, canon, depth);
  }

  void load_text(const std::string& text, const std::string& name, const std::string& canon, int depth) {
    stack_.push_back(canon);
    stack_names_.push_back(name);
    prog_.files.push_back(name);
    if (prog_.path.empty()) prog_.path = name;
    const std::string saved_dir = dir_;
    dir_ = fs::path(name).parent_path().string();
    int lineno = 0;
    bool seen_version = false;
    std::size_t pos = 0;
    while (pos <= text.size()) {
      std::size_t nl = text.find('\n', pos);
      if (nl == std::string::npos) nl = text.size();
      std::string raw = text.substr(pos, nl - pos);
      pos = nl + 1;
      ++lineno;
      if (++total_lines_ > kMaxTraceLines)
        throw TraceError({name, lineno, 1}, std::string("trace is longer than ") + std::to_string(kMaxTraceLines) + " lines (includes expanded)", raw);
      if (!raw.empty() && raw.back() == '\r') raw.pop_back();
      Line l;
      l.where = {name, lineno, 1};
      l.text = raw;
      l.tok = tokenize_line(raw, l.where);
      if (l.tok.empty()) {
        if (nl == text.size()) break;
        continue;
      }
      if (!seen_version) {
        version_line(l);
        seen_version = true;
      } else {
        command(l, depth);
      }
      if (nl == text.size()) break;
    }
    if (!seen_version)
      throw TraceError({name, 1, 1}, std::string("empty trace: expected the version line `ffsim-trace ") + std::to_string(kTraceVersion) + "`");
    dir_ = saved_dir;
    stack_.pop_back();
    stack_names_.pop_back();
  }

 private:
  template <class F>
  void check_root(const std::string& path, F&& fail) {
    if (opt_.file_root.empty()) return;
    std::error_code ec;
    const fs::path root = fs::weakly_canonical(opt_.file_root, ec);
    const fs::path p = fs::weakly_canonical(path, ec);
    const std::string r = root.string(), s = p.string();
    if (s.size() <= r.size() || s.compare(0, r.size(), r) != 0 || (s[r.size()] != '/' && r.back() != '/'))
      throw fail(std::string("`") + path + "` is outside the allowed directory " + opt_.file_root);
  }

  std::string resolve(const std::string& p) const {
    if (fs::path(p).is_absolute() || dir_.empty()) return p;
    return (fs::path(dir_) / p).string();
  }

  [[noreturn]] void fail(const Line& l, std::size_t k, const std::string& m) const { throw TraceError(l.at(k), m, l.text); }

  void version_line(const Line& l) {
    const std::string want = std::string("ffsim-trace ") + std::to_string(kTraceVersion);
    if (l.tok[0].text != "ffsim-trace") fail(l, 0, std::string("expected the version line `") + want + "` first");
    if (l.tok.size() != 2) fail(l, l.tok.size() > 2 ? 2 : 0, std::string("the version line is `") + want + "`");
    if (l.tok[1].text != std::to_string(kTraceVersion))
      fail(l, 1, std::string("unsupported trace version `") + l.tok[1].text + "`; this ffsim reads version " + std::to_string(kTraceVersion));
  }

  std::optional<double> lookup(const std::string& n) const {
    auto it = values_.find(n);
    if (it == values_.end()) return std::nullopt;
    return it->second;
  }
  Expression::Lookup lookup_fn() const {
    return [this](const std::string& n) { return lookup(n); };
  }

  double eval(const Line& l, std::size_t k) const {
    return Expression::parse(l.tok[k].text, l.at(k), l.text).eval(lookup_fn());
  }
  long long eval_int(const Line& l, std::size_t k, const std::string& what, long long lo, long long hi) const {
    const double v = eval(l, k);
    if (v != std::floor(v)) fail(l, k, what + " must be an integer, got " + format_number(v));
    if (v < static_cast<double>(lo) || v > static_cast<double>(hi))
      fail(l, k, what + " must be in [" + std::to_string(lo) + ", " + std::to_string(hi) + "], got " + format_number(v));
    return static_cast<long long>(v);
  }

  void expect_count(const Line& l, std::size_t min, std::size_t max, const std::string& usage) const {
    const std::size_t n = l.tok.size() - 1;
    if (n < min) throw TraceError(l.end(), std::string("`") + l.tok[0].text + "` needs more arguments: " + usage, l.text);
    if (n > max) fail(l, max + 1, std::string("too many arguments: ") + usage);
  }

  std::string new_name(const Line& l, std::size_t k, const char* what) {
    const std::string& n = l.tok[k].text;
    if (!is_identifier(n)) fail(l, k, std::string("bad ") + what + " name `" + n + "` (letters, digits and _, not starting with a digit)");
    return n;
  }

  // The set-up is fixed by the first GL command or output.
  void freeze() {
    if (frozen_) return;
    frozen_ = true;
    if (!opt_.profile.empty()) {
      try {
        prog_.profile = load_profile(opt_.profile);
        prog_.profile_spec = opt_.profile;
      } catch (const ProfileError& e) {
        throw TraceError({"--profile", 1, 1}, e.what(), opt_.profile);
      }
    } else if (!profile_set_) {
      prog_.profile = load_profile("geforce256");
    }
    if (opt_.size) {
      prog_.width = opt_.size->first;
      prog_.height = opt_.size->second;
    }
    const long long px = static_cast<long long>(prog_.width) * prog_.height;
    if (prog_.width < 1 || prog_.height < 1 || prog_.width > kMaxFramebufferSide || prog_.height > kMaxFramebufferSide ||
        px > opt_.max_pixels) {
      const std::string m = std::string("framebuffer size ") + std::to_string(prog_.width) + "x" + std::to_string(prog_.height) +
                            std::string(" is out of range (1..") + std::to_string(kMaxFramebufferSide) + " per side, at most " +
                            std::to_string(opt_.max_pixels) + " pixels)";
      if (opt_.size) throw TraceError({"--size", 1, 1}, m);
      throw TraceError(size_at_, m, size_line_);
    }
  }

  void require_unfrozen(const Line& l, const SourceLoc& previous) const {
    if (!previous.empty()) fail(l, 0, std::string("`") + l.tok[0].text + "` is already set at " + previous.str());
    if (frozen_) fail(l, 0, std::string("`") + l.tok[0].text + "` must come before the first GL command or output");
  }

  BufferKind buffer_kind(const Line& l, std::size_t k) const {
    const std::string& s = l.tok[k].text;
    BufferKind b;
    if (s == "color") b = BufferKind::Color;
    else if (s == "alpha") b = BufferKind::Alpha;
    else if (s == "stencil") b = BufferKind::Stencil;
    else if (s == "depth") b = BufferKind::Depth;
    else if (s == "image" && l.tok[0].text == "dump") fail(l, k, "`dump image` takes a name and a file: dump image NAME FILE");
    else fail(l, k, std::string("expected a buffer: color, alpha, stencil or depth; got `") + s + "`");
    if (b == BufferKind::Stencil && prog_.profile.stencil_bits == 0)
      fail(l, k, std::string("the framebuffer has no stencil buffer (profile ") + prog_.profile.name + ")");
    if (b == BufferKind::Depth && prog_.profile.depth_bits == 0)
      fail(l, k, std::string("the framebuffer has no depth buffer (profile ") + prog_.profile.name + ")");
    return b;
  }

  Step step(const Line& l, StepKind kind) {
    freeze();
    Step s;
    s.kind = kind;
    s.where = l.at(0);
    s.line_text = l.text;
    s.name = l.tok[0].text;
    return s;
  }

  void command(const Line& l, int depth) {
    const std::string& c = l.tok[0].text;
    if (l.tok[0].quoted) fail(l, 0, "a command name cannot be quoted");
    if (c == "ffsim-trace") fail(l, 0, "the version line may appear only once, first in the file");
    else if (c == "param") param(l);
    else if (c == "framebuffer") framebuffer(l);
    else if (c == "profile") profile(l);
    else if (c == "include") include(l, depth);
    else if (c == "image") image(l);
    else if (c == "generate") generate(l);
    else if (c == "table") table(l);
    else if (c == "dump") dump(l);
    else if (c == "hash") hash(l);
    else if (c == "expect") expect(l);
    else if (const CommandDef* d = cmds_.find(c)) gl_call(l, *d);
    else fail(l, 0, std::string("unknown command `") + c + "`");
  }

  void param(const Line& l) {
    if (l.tok.size() < 3) throw TraceError(l.end(), "`param` needs a name and a default: param NAME DEFAULT [description]", l.text);
    const std::string name = new_name(l, 1, "parameter");
    for (const auto& p : prog_.params)
      if (p.name == name) fail(l, 1, std::string("parameter `") + name + "` is already declared at " + p.where.str());
    Param p;
    p.name = name;
    p.where = l.at(1);
    p.default_value = eval(l, 2);
    p.value = p.default_value;
    for (std::size_t k = 3; k < l.tok.size(); ++k) p.description += std::string(k > 3 ? " " : "") + l.tok[k].text;
    if (auto it = sets_.find(name); it != sets_.end()) {
      const std::string line = name + "=" + it->second;
      p.value = Expression::parse(it->second, {"--set", 1, static_cast<int>(name.size()) + 2}, line).eval(lookup_fn());
      p.overridden = true;
      used_sets_.insert(name);
    }
    values_[name] = p.value;
    prog_.params.push_back(std::move(p));
  }

  void framebuffer(const Line& l) {
    require_unfrozen(l, size_at_);
    expect_count(l, 2, 2, "framebuffer WIDTH HEIGHT");
    prog_.width = static_cast<int>(eval_int(l, 1, "the width", 1, kMaxFramebufferSide));
    prog_.height = static_cast<int>(eval_int(l, 2, "the height", 1, kMaxFramebufferSide));
    size_at_ = l.at(0);
    size_line_ = l.text;
  }

  void profile(const Line& l) {
    require_unfrozen(l, profile_at_);
    expect_count(l, 1, 1, "profile NAME|FILE");
    profile_at_ = l.at(0);
    profile_set_ = true;
    if (!opt_.profile.empty()) return;  // the command line wins; the trace's choice is not read
    const std::string spec = l.tok[1].text;
    std::string source = spec;
    if (!find_builtin_profile(spec)) {
      source = resolve(spec);
      check_root(source, [&](const std::string& m) { return TraceError(l.at(1), m, l.text); });
    }
    try {
      prog_.profile = load_profile(source);
    } catch (const ProfileError& e) {
      fail(l, 1, e.what());
    }
    prog_.profile_spec = spec;
  }

  void include(const Line& l, int depth) {
    expect_count(l, 1, 1, "include FILE");
    if (depth + 1 > kMaxIncludeDepth) fail(l, 0, std::string("includes nested more than ") + std::to_string(kMaxIncludeDepth) + " deep");
    load_file(resolve(l.tok[1].text), &l, 1, depth + 1);
  }

  void add_resource(const Line& l, const std::string& name, std::string kind, std::string source, Image im) {
    const long long px = static_cast<long long>(im.width) * im.height;
    if (px > opt_.max_pixels)
      fail(l, 2, std::string("image size ") + std::to_string(im.width) + "x" + std::to_string(im.height) + " exceeds the limit of " +
                     std::to_string(opt_.max_pixels) + " pixels");
    Resource r;
    r.name = name;
    r.kind = std::move(kind);
    r.source = std::move(source);
    r.where = l.at(1);
    r.image = std::make_shared<const Image>(std::move(im));
    resources_[name] = prog_.resources.size();
    prog_.resources.push_back(std::move(r));
  }

  std::string resource_name(const Line& l) {
    const std::string name = new_name(l, 1, "image");
    if (auto it = resources_.find(name); it != resources_.end())
      fail(l, 1, std::string("image `") + name + "` is already defined at " + prog_.resources[it->second].where.str());
    return name;
  }

  void image(const Line& l) {
    expect_count(l, 2, 2, "image NAME FILE");
    const std::string name = resource_name(l);
    const std::string path = resolve(l.tok[2].text);
    check_root(path, [&](const std::string& m) { return TraceError(l.at(2), m, l.text); });
    std::error_code ec;
    if (fs::exists(path, ec) && !fs::is_regular_file(path, ec)) fail(l, 2, path + ": not a regular file");
    try {
      add_resource(l, name, "image", path, read_image(path));
    } catch (const ImageError& e) {
      fail(l, 2, e.what());
    }
  }

  void generate(const Line& l) {
    if (l.tok.size() < 3) throw TraceError(l.end(), "`generate` needs a name and a generator: generate NAME GENERATOR key=value ...", l.text);
    const std::string name = resource_name(l);
    const GeneratorDef* g = generators().find(l.tok[2].text);
    if (!g) {
      std::vector<std::string> names;
      for (const auto& [n, d] : generators().all()) names.push_back(n);
      fail(l, 2, std::string("unknown generator `") + l.tok[2].text + "` (this build has " + join_or(names) + ")");
    }
    std::map<std::string, GeneratorArgs::Value> values;
    for (std::size_t k = 3; k < l.tok.size(); ++k) {
      const std::string& t = l.tok[k].text;
      const auto eq = t.find('=');
      if (eq == std::string::npos || eq == 0 || l.tok[k].quoted) fail(l, k, std::string("expected key=value, got `") + t + "`");
      const std::string key = t.substr(0, eq);
      if (values.count(key)) fail(l, k, std::string("key `") + key + "` is given twice");
      values[key] = {t.substr(eq + 1), {l.where.file, l.where.line, l.tok[k].column + static_cast<int>(eq) + 1}, false};
    }
    GeneratorArgs args(std::move(values), lookup_fn(), l.text, opt_.max_pixels);
    Image im;
    try {
      im = g->make(args);
    } catch (const TraceError&) {
      throw;
    } catch (const std::exception& e) {
      fail(l, 2, g->name + ": " + e.what());
    }
    add_resource(l, name, "generate", g->name, std::move(im));
  }

  void table(const Line& l) {
    if (l.tok.size() < 4) throw TraceError(l.end(), "`table` needs a name, a width and 1 to 4 expressions: table NAME WIDTH EXPR...", l.text);
    expect_count(l, 3, 6, "table NAME WIDTH EXPR [EXPR EXPR EXPR]");
    const std::string name = resource_name(l);
    const long long limit = std::min<long long>(kMaxTableWidth, opt_.max_pixels);
    const int width = static_cast<int>(eval_int(l, 2, "the table width", 1, limit));
    const int channels = static_cast<int>(l.tok.size()) - 3;
    std::vector<Expression> ex;
    std::string source;
    for (std::size_t k = 3; k < l.tok.size(); ++k) {
      ex.push_back(Expression::parse(l.tok[k].text, l.at(k), l.text));
      source += std::string(k > 3 ? " " : "") + l.tok[k].text;
    }
    Image im = Image::make(width, 1, channels, SampleType::F32);
    double i = 0, x = 0;
    const double n = width;
    auto lk = [&](const std::string& s) -> std::optional<double> {
      if (s == "i") return i;
      if (s == "x") return x;
      if (s == "n") return n;
      return lookup(s);
    };
    for (int k = 0; k < width; ++k) {
      i = k;
      x = width > 1 ? static_cast<double>(k) / (width - 1) : 0.0;
      for (int c = 0; c < channels; ++c) {
        double v;
        try {
          v = ex[static_cast<std::size_t>(c)].eval(lk);
        } catch (const TraceError& e) {
          throw TraceError(e.where(), e.message() + " (at i = " + std::to_string(k) + ")", e.line_text());
        }
        // Converting a double beyond the binary32 range to float is undefined: check first.
        if (!(std::fabs(v) <= static_cast<double>(std::numeric_limits<float>::max())))
          fail(l, 3 + static_cast<std::size_t>(c), std::string("value ") + format_number(v) + " at i = " + std::to_string(k) + " is outside the binary32 range");
        im.f32[im.index(k, 0, c)] = static_cast<float>(v);
      }
    }
    add_resource(l, name, "table", source, std::move(im));
  }

  // A dump's FILE (token k): relative, inside the output directory, a known
  // extension, not under passes/, not written twice. Returns the normalised path.
  std::string dump_file(const Line& l, std::size_t k) {
    const std::string& f = l.tok[k].text;
    const fs::path p(f);
    bool bad = f.empty() || p.is_absolute() || f.back() == '/';
    for (const auto& part : p)
      if (!part.empty() && part.string()[0] == '.') bad = true;  // `..`, `.`, hidden names (temporaries)
    if (bad) fail(l, k, std::string("dump file `") + f + "` must be a relative path inside the output directory (no `..`, no names starting with `.`)");
    std::string ext = p.extension().string();
    for (auto& ch : ext) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
    if (ext != ".png" && ext != ".exr" && ext != ".tif" && ext != ".tiff")
      fail(l, k, std::string("dump file `") + f + "` needs the extension .png, .exr, .tif or .tiff");
    if (f.rfind("passes/", 0) == 0) fail(l, k, "the directory passes/ is reserved for --dump-each-pass");
    if (auto it = dump_files_.find(p.lexically_normal().string()); it != dump_files_.end())
      fail(l, k, std::string("`") + f + "` is already written by the dump at " + it->second.str());
    dump_files_[p.lexically_normal().string()] = l.at(0);
    return p.lexically_normal().string();
  }

  // The client image named by token k, as an Image argument of step `arg`.
  const Resource& image_argument(const Line& l, std::size_t k, ArgValue& arg) {
    auto it = resources_.find(l.tok[k].text);
    if (it == resources_.end())
      fail(l, k, std::string("unknown image `") + l.tok[k].text + "` (define it with image, generate, table or glReadPixels)");
    const Resource& r = prog_.resources[it->second];
    arg.kind = ArgKind::Image;
    arg.text = r.name;
    arg.where = l.at(k);
    arg.image = r.image;
    arg.client_memory = r.client_memory;
    return r;
  }

  void dump(const Line& l) {
    if (l.tok.size() >= 2 && l.tok[1].text == "image") {
      expect_count(l, 3, 3, "dump image NAME FILE");
      Step s = step(l, StepKind::DumpImage);
      image_argument(l, 2, s.image);
      s.file = dump_file(l, 3);
      prog_.steps.push_back(std::move(s));
      return;
    }
    expect_count(l, 2, 2, "dump color|alpha|stencil|depth FILE  or  dump image NAME FILE");
    Step s = step(l, StepKind::Dump);
    s.buffer = buffer_kind(l, 1);
    s.file = dump_file(l, 2);
    prog_.steps.push_back(std::move(s));
  }

  void hash(const Line& l) {
    expect_count(l, 1, 1, "hash color|alpha|stencil|depth");
    Step s = step(l, StepKind::Hash);
    s.buffer = buffer_kind(l, 1);
    prog_.steps.push_back(std::move(s));
  }

  void expect(const Line& l) {
    if (l.tok.size() < 2) throw TraceError(l.end(), "`expect` needs what to check: hash, pixel, image, error or enabled", l.text);
    const std::string& what = l.tok[1].text;
    // The optional `tol T` that ends `expect pixel` and `expect image`, starting at token k.
    auto read_tolerance = [&](std::size_t k, Step& s) {
      if (k >= l.tok.size()) return;
      if (k + 2 != l.tok.size()) {
        if (k + 1 == l.tok.size()) throw TraceError(l.end(), "`tol` needs a value", l.text);
        fail(l, k + 2, "nothing may follow `tol T`");
      }
      s.tol = eval(l, k + 1);
      if (s.tol < 0) fail(l, k + 1, std::string("the tolerance must not be negative, got ") + format_number(s.tol));
    };
    if (what == "hash") {
      expect_count(l, 3, 3, "expect hash color|alpha|stencil|depth HEX");
      Step s = step(l, StepKind::ExpectHash);
      s.buffer = buffer_kind(l, 2);
      const std::string& h = l.tok[3].text;
      bool ok = h.size() == 16;
      for (char ch : h) ok = ok && std::isxdigit(static_cast<unsigned char>(ch));
      if (!ok) fail(l, 3, std::string("expected a hash of 16 hex digits, got `") + h + "`");
      s.hash = std::stoull(h, nullptr, 16);
      prog_.steps.push_back(std::move(s));
    } else if (what == "pixel") {
      if (l.tok.size() < 5) throw TraceError(l.end(), "`expect pixel` needs X Y BUFFER VALUES...: expect pixel X Y color|alpha|stencil|depth V... [tol T]", l.text);
      Step s = step(l, StepKind::ExpectPixel);
      s.x = static_cast<int>(eval_int(l, 2, "x", 0, prog_.width - 1));
      s.y = static_cast<int>(eval_int(l, 3, "y", 0, prog_.height - 1));
      s.buffer = buffer_kind(l, 4);
      const std::size_t want = s.buffer == BufferKind::Color ? 4 : 1;
      std::size_t k = 5;
      for (; k < l.tok.size() && l.tok[k].text != "tol"; ++k) {
        if (s.values.size() == want) fail(l, k, std::string("too many values: ") + buffer_kind_name(s.buffer) + " has " + std::to_string(want));
        s.values.push_back(eval(l, k));
      }
      if (s.values.size() < want)
        throw TraceError(k < l.tok.size() ? l.at(k) : l.end(),
                         std::string("expected ") + std::to_string(want) + " value" + std::string(want > 1 ? "s" : "") + " for " +
                             buffer_kind_name(s.buffer) + ", got " + std::to_string(s.values.size()),
                         l.text);
      read_tolerance(k, s);
      prog_.steps.push_back(std::move(s));
    } else if (what == "image") {
      if (l.tok.size() < 6) throw TraceError(l.end(), "`expect image` needs NAME X Y VALUES...: expect image NAME X Y V... [tol T]", l.text);
      Step s = step(l, StepKind::ExpectImage);
      const Resource& r = image_argument(l, 2, s.image);
      const Image& im = *r.image;
      if (im.width < 1 || im.height < 1) fail(l, 2, std::string("image `") + r.name + "` has no pixels");
      s.x = static_cast<int>(eval_int(l, 3, "x", 0, im.width - 1));
      s.y = static_cast<int>(eval_int(l, 4, "y", 0, im.height - 1));
      const std::size_t want = static_cast<std::size_t>(im.channels);
      std::size_t k = 5;
      for (; k < l.tok.size() && l.tok[k].text != "tol"; ++k) {
        if (s.values.size() == want) fail(l, k, cat("too many values: image `", r.name, "` has ", std::to_string(want), " channel", want > 1 ? "s" : ""));
        s.values.push_back(eval(l, k));
      }
      if (s.values.size() < want)
        throw TraceError(k < l.tok.size() ? l.at(k) : l.end(),
                         cat("expected ", std::to_string(want), " value", want > 1 ? "s" : "", " for image `", r.name, "`, got ",
                             std::to_string(s.values.size())),
                         l.text);
      read_tolerance(k, s);
      prog_.steps.push_back(std::move(s));
    } else if (what == "error") {
      expect_count(l, 2, 2, "expect error GL_NO_ERROR|GL_INVALID_ENUM|...");
      Step s = step(l, StepKind::ExpectError);
      s.error = enum_token(l, 2, "error", {});
      prog_.steps.push_back(std::move(s));
    } else if (what == "enabled") {
      expect_count(l, 3, 3, "expect enabled CAPABILITY 0|1");
      Step s = step(l, StepKind::ExpectEnabled);
      s.error = enum_token(l, 2, "the capability", {});
      s.enabled = boolean(l, 3, "the state");
      prog_.steps.push_back(std::move(s));
    } else {
      fail(l, 1, std::string("expected hash, pixel, image, error or enabled after `expect`, got `") + what + "`");
    }
  }

  GLenum enum_token(const Line& l, std::size_t k, const std::string& what, const std::vector<GLenum>& allowed) const {
    const std::string& t = l.tok[k].text;
    if (!t.empty() && ((t[0] >= 'A' && t[0] <= 'Z') || (t[0] >= 'a' && t[0] <= 'z') || t[0] == '_')) {
      const auto v = gl::enum_value(t);
      if (!v) fail(l, k, std::string("unknown GL enum `") + t + "`");
      if (!allowed.empty() && std::find(allowed.begin(), allowed.end(), *v) == allowed.end()) {
        std::vector<std::string> names;
        for (GLenum a : allowed) names.push_back(gl::enum_name(a));
        fail(l, k, std::string("`") + t + "` is not allowed for " + what + " (expected " + join_or(names) + ")");
      }
      return *v;
    }
    // A number or an expression: passed to the GL unchecked, like a number. Inside
    // it, names starting with GL_ are enum values (parameters are looked up first),
    // so a parameter can select a token: (GL_NEAREST+filter).
    const double v = Expression::parse(t, l.at(k), l.text).eval([this](const std::string& n) -> std::optional<double> {
      if (auto p = lookup(n)) return p;
      if (n.rfind("GL_", 0) == 0)
        if (const auto e = gl::enum_value(n)) return static_cast<double>(*e);
      return std::nullopt;
    });
    if (v != std::floor(v)) fail(l, k, what + " must be an integer, got " + format_number(v));
    if (v < 0 || v > static_cast<double>(0xFFFFFFFFll))
      fail(l, k, what + " must be in [0, 4294967295], got " + format_number(v));
    return static_cast<GLenum>(static_cast<long long>(v));
  }

  void gl_call(const Line& l, const CommandDef& d) {
    Step s = step(l, StepKind::Call);
    s.def = &d;
    const std::size_t given = l.tok.size() - 1;
    std::size_t fixed = 0;
    bool rest = false;
    for (const auto& a : d.args) {
      if (a.kind == ArgKind::Numbers) {
        if (a.count == 0) rest = true;
        else fixed += static_cast<std::size_t>(a.count);
      } else {
        ++fixed;
      }
    }
    if (given < fixed + (rest ? 1 : 0) || (!rest && given > fixed)) {
      std::string names = d.signature().substr(d.name.size());
      if (!names.empty()) names = cat(" (", names.substr(1), ")");
      const std::size_t need = fixed + (rest ? 1 : 0);
      const std::string m = cat(d.name, " takes ", rest ? "at least " : "", std::to_string(need), " argument",
                                need == 1 ? "" : "s", names, ", got ", std::to_string(given));
      if (given > fixed && !rest) fail(l, fixed + 1, m);
      throw TraceError(l.at(0), m, l.text);
    }
    std::size_t k = 1;
    std::optional<std::size_t> out_arg;
    for (const auto& a : d.args) {
      const std::string what = std::string("`") + a.name + "` of " + d.name;
      ArgValue v;
      v.kind = a.kind;
      v.where = l.at(k);
      v.text = l.tok[k].text;
      switch (a.kind) {
        case ArgKind::Enum: v.i = enum_token(l, k, what, a.allowed); ++k; break;
        case ArgKind::Int: v.i = eval_int(l, k, what, a.min, a.max); ++k; break;
        case ArgKind::Float: v.f = eval(l, k); ++k; break;
        case ArgKind::Float32: v.f = to_float32(l, k, what, eval(l, k)); ++k; break;
        case ArgKind::Bool: v.i = boolean(l, k, what) ? 1 : 0; ++k; break;
        case ArgKind::Bitfield: v.i = bitfield(l, k, what, a.allowed); ++k; break;
        case ArgKind::Image: {
          auto it = resources_.find(l.tok[k].text);
          if (it == resources_.end()) fail(l, k, std::string("unknown image `") + l.tok[k].text + "` (define it with image, generate or table)");
          v.image = prog_.resources[it->second].image;
          v.client_memory = prog_.resources[it->second].client_memory;
          ++k;
          break;
        }
        case ArgKind::OutImage: {
          if (l.tok[k].quoted || !is_identifier(l.tok[k].text))
            fail(l, k, std::string("bad image name `") + l.tok[k].text + "` (letters, digits and _, not starting with a digit)");
          v.client_memory = true;
          out_arg = s.args.size();
          ++k;
          break;
        }
        case ArgKind::Numbers: {
          const std::size_t n = a.count ? static_cast<std::size_t>(a.count) : l.tok.size() - k;
          for (std::size_t j = 0; j < n; ++j, ++k) {
            const double x = eval(l, k);
            v.list.push_back(a.float32 ? to_float32(l, k, what, x) : x);
          }
          break;
        }
      }
      s.args.push_back(std::move(v));
    }
    if (d.check)
      if (auto problem = d.check(s.args)) throw TraceError(s.args.at(problem->arg).where, problem->message, l.text);
    if (out_arg) declare_client_memory(l, d, s.args, *out_arg);
    prog_.steps.push_back(std::move(s));
  }

  // The client memory an OutImage argument names: declared by the first call, and
  // the same shape for every later call writing it.
  void declare_client_memory(const Line& l, const CommandDef& d, std::vector<ArgValue>& args, std::size_t k) {
    ArgValue& v = args[k];
    if (!d.out_shape) throw BindError(d.name + ": an OutImage argument needs writes_image()");
    Image im = d.out_shape(args);
    const long long px = static_cast<long long>(im.width) * im.height;
    if (px > opt_.max_pixels)
      throw TraceError(v.where, cat("image size ", std::to_string(im.width), "x", std::to_string(im.height),
                                    " exceeds the limit of ", std::to_string(opt_.max_pixels), " pixels"), l.text);
    auto describe = [](const Image& i) {
      const char* t = i.type == SampleType::U8 ? "8-bit" : i.type == SampleType::U16 ? "16-bit" : "float";
      return cat(std::to_string(i.width), "x", std::to_string(i.height), " ", t, " with ", std::to_string(i.channels),
                 " channel", i.channels == 1 ? "" : "s");
    };
    if (auto it = resources_.find(v.text); it != resources_.end()) {
      const Resource& r = prog_.resources[it->second];
      if (!r.client_memory)
        throw TraceError(v.where, cat("image `", v.text, "` (", r.kind, " at ", r.where.str(), ") is not client memory ", d.name,
                                      " may write; name a new image"), l.text);
      const Image& old = *r.image;
      if (old.width != im.width || old.height != im.height || old.channels != im.channels || old.type != im.type)
        throw TraceError(v.where, cat("client image `", v.text, "` is ", describe(old), " (declared at ", r.where.str(), "); ",
                                      d.name, " here writes ", describe(im)), l.text);
      v.image = r.image;
      return;
    }
    Resource r;
    r.name = v.text;
    r.kind = "readback";
    r.source = d.name;
    r.where = v.where;
    r.client_memory = true;
    r.image = std::make_shared<const Image>(std::move(im));
    v.image = r.image;
    resources_[r.name] = prog_.resources.size();
    prog_.resources.push_back(std::move(r));
  }

  double to_float32(const Line& l, std::size_t k, const std::string& what, double v) const {
    // Converting a double beyond the binary32 range to float is undefined: check first.
    if (!(std::fabs(v) <= static_cast<double>(std::numeric_limits<float>::max())))
      fail(l, k, what + " is outside the binary32 range (" + format_number(v) + ")");
    return static_cast<float>(v);
  }

  bool boolean(const Line& l, std::size_t k, const std::string& what) const {
    const std::string& t = l.tok[k].text;
    if (t == "1" || t == "GL_TRUE" || t == "TRUE") return true;
    if (t == "0" || t == "GL_FALSE" || t == "FALSE") return false;
    fail(l, k, std::string("expected 0, 1, GL_TRUE or GL_FALSE for ") + what + ", got `" + t + "`");
  }

  std::int64_t bitfield(const Line& l, std::size_t k, const std::string& what, const std::vector<GLenum>& bits) const {
    const std::string& t = l.tok[k].text;
    std::int64_t v = 0;
    std::size_t start = 0;
    for (;;) {
      const std::size_t bar = t.find('|', start);
      const std::string part = t.substr(start, bar == std::string::npos ? std::string::npos : bar - start);
      const SourceLoc at{l.where.file, l.where.line, l.tok[k].column + static_cast<int>(start)};
      if (part.empty()) throw TraceError(at, std::string("empty part in the bitfield ") + what, l.text);
      if ((part[0] >= 'A' && part[0] <= 'Z') || (part[0] >= 'a' && part[0] <= 'z') || part[0] == '_') {
        const auto e = gl::enum_value(part);
        if (!e) throw TraceError(at, std::string("unknown GL enum `") + part + "`", l.text);
        if (!bits.empty() && std::find(bits.begin(), bits.end(), *e) == bits.end()) {
          std::vector<std::string> names;
          for (GLenum b : bits) names.push_back(bit_name(b));
          throw TraceError(at, std::string("`") + part + "` is not allowed in " + what + " (expected " + join_or(names) + ")", l.text);
        }
        v |= *e;
      } else {
        const double x = Expression::parse(part, at, l.text).eval(lookup_fn());
        if (x != std::floor(x) || x < 0 || x > 4294967295.0)
          throw TraceError(at, what + " must be an integer in [0, 4294967295], got " + format_number(x), l.text);
        v |= static_cast<std::int64_t>(x);
      }
      if (bar == std::string::npos) break;
      start = bar + 1;
    }
    return v;
  }

  const LoadOptions& opt_;
  const CommandTable& cmds_;
  Program prog_;
  std::map<std::string, std::string> sets_;
  std::set<std::string> used_sets_;
  std::map<std::string, double> values_;
  std::map<std::string, std::size_t> resources_;
  std::map<std::string, SourceLoc> dump_files_;
  std::vector<std::string> stack_, stack_names_;
  std::string dir_;
  long long total_lines_ = 0;
  std::uintmax_t total_bytes_ = 0;
  bool frozen_ = false, profile_set_ = false;
  SourceLoc size_at_, profile_at_;
  std::string size_line_;
};

}  // namespace

Program load_trace_file(const std::string& path, const LoadOptions& options) {
  Loader l(options);
  l.load_file(path, nullptr, 0, 0);
  return l.finish();
}

Program load_trace_text(const std::string& text, const std::string& name, const LoadOptions& options) {
  Loader l(options);
  if (text.size() > kMaxTraceFileBytes)
    throw TraceError({}, name + ": larger than " + std::to_string(kMaxTraceFileBytes) + " bytes");
  l.load_text(text, name, std::string("<text>") + name, 0);
  return l.finish();
}

}  // namespace ffsim::trace
