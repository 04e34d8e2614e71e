// Loading a command trace: lexing, includes, parameters, expressions, set-up
// commands, client images, and the typed arguments of every GL call. Loading
// evaluates everything that does not need the GL (expressions, tables, images,
// argument types and enums), so a trace with any error in it is rejected before a
// single command runs or a file is written. Format: docs/trace-format.md.
#pragma once
#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "pipeline/number/profile.h"
#include "sim/framebuffer.h"
#include "sim/hash.h"
#include "sim/image_io.h"
#include "sim/trace/binder.h"
#include "sim/trace/error.h"

namespace ffsim::trace {

inline constexpr int kTraceVersion = 1;
inline constexpr int kMaxIncludeDepth = 16;
inline constexpr std::size_t kMaxTraceFileBytes = 4u << 20;  // per file
inline constexpr long long kMaxTraceLines = 1000000;         // all files together, includes expanded
inline constexpr std::uintmax_t kMaxTraceTotalBytes = 64u << 20;  // all files together, includes expanded
inline constexpr int kMaxTableWidth = 65536;

inline constexpr std::uint32_t kNotPacked = 0xFFFFFFFFu;

enum class StepKind { Call, Dump, DumpImage, Hash, ExpectHash, ExpectPixel, ExpectImage, ExpectError, ExpectEnabled };

struct Step {
  // What the replay loop reads for every call, first: one 64-byte line of a step
  // (the rest of the step is read only for messages and non-call steps).
  StepKind kind = StepKind::Call;
  std::uint32_t packed_at = kNotPacked;  // Call: its arguments' PackedArg in Program::packed
  const CommandDef* def = nullptr;       // Call
  std::vector<ArgValue> args;            // Call
  SourceLoc where;        // the command's first token
  std::string line_text;  // the whole line, for messages
  std::string name;       // the command as written: "glClear", "dump", "expect", ...
  BufferKind buffer = BufferKind::Color;  // Dump, Hash, ExpectHash, ExpectPixel
  std::string file;                       // Dump, DumpImage: path relative to the output directory
  ArgValue image;                         // DumpImage, ExpectImage: the client image (text = its name)
  std::uint64_t hash = 0;                 // ExpectHash
  int x = 0, y = 0;                       // ExpectPixel, ExpectImage
  std::vector<double> values;             // ExpectPixel: 4 for color, 1 otherwise; ExpectImage: one per channel
  double tol = 0;                         // ExpectPixel, ExpectImage
  GLenum error = gl::NO_ERROR;            // ExpectError; ExpectEnabled: the capability
  bool enabled = false;                   // ExpectEnabled
  bool is_pass() const { return kind == StepKind::Call && def && def->is_pass; }
};

// What the replay loop reads of each step, contiguous: a Step is 384 bytes, and
// a frame of the terrain replays 33000 of them, about 13 MB a frame; these are
// 32 (docs/performance.md 16).
struct StepHot {
  const CommandDef* def = nullptr;               // Call
  CommandDef::PackedFn packed_call = nullptr;    // Call: def->packed_call when its arguments are packed
  std::uint32_t packed_at = kNotPacked;          // Call: as Step::packed_at
  StepKind kind = StepKind::Call;
  bool vertex_data = false;                      // Call: def->vertex_data
  // The number of steps from this one on (at most 65535) that are packed
  // vertex-data calls which cannot record a GL error under the program's profile
  // (CommandDef::never_errs, or errs_on_unit with a unit of the profile): the
  // replay calls them one after the other without the per-step bookkeeping.
  std::uint16_t quiet_run = 0;
  // A quiet run's first step: its class in Program::vertex_runs, plus one (0:
  // not memoized; vertex_runs).
  std::uint32_t run_class = 0;
};
static_assert(sizeof(StepHot) <= 32);

// The vertex-run memo's name for a class of equal quiet runs (unique in the
// process) and how their calls use the current attributes (sim/vertex_run_memo.h).
struct VertexRun {
  std::uint64_t id = 0;
  VertexRunUsage usage;
};

struct Param {
  std::string name;
  double default_value = 0;
  double value = 0;  // after --set
  bool overridden = false;
  std::string description;
  SourceLoc where;
};

struct Resource {
  std::string name;
  std::string kind;    // "image", "generate", "table", "readback"
  std::string source;  // file path, generator name, table expressions, or the writing command
  bool client_memory = false;  // written while the trace runs (glReadPixels); `image` is its zero-filled start
  SourceLoc where;
  std::shared_ptr<const Image> image;
};

struct Program {
  std::string path;  // the top-level trace
  int width = 256, height = 256;
  Profile profile;
  std::string profile_spec = "geforce256";  // as named in the trace or on the command line
  std::vector<Param> params;
  std::vector<Resource> resources;
  std::vector<Step> steps;
  std::vector<StepHot> hot;        // one per step (hot_steps), made when loaded
  std::vector<PackedArg> packed;   // the calls' scalar arguments, in step order (Step::packed_at)
  std::vector<VertexRun> vertex_runs;  // StepHot::run_class (vertex_runs), made when loaded
  std::vector<std::string> files;  // every trace file read, in order
  // The PackedArg of step s's arguments, or null (not a call, or not packed).
  const PackedArg* packed_args(const Step& s) const {
    return s.packed_at != kNotPacked && s.packed_at + s.args.size() <= packed.size() ? packed.data() + s.packed_at : nullptr;
  }
  int pass_count() const;
};

struct LoadOptions {
  std::vector<std::pair<std::string, std::string>> sets;  // --set NAME=EXPR, in order
  std::string profile;                                    // --profile NAME|FILE (overrides the trace)
  std::optional<std::pair<int, int>> size;                // --size WxH (overrides `framebuffer`)
  long long max_pixels = kMaxFramebufferPixels;           // framebuffer, images and tables
  std::string file_root;  // non-empty: every file read must lie under this directory
  const CommandTable* commands = nullptr;  // default: gl_commands()
};

// The StepHot of each of p's steps.
std::vector<StepHot> hot_steps(const Program& p);
// The classes of p's quiet runs of at least a few calls (runs of equal calls
// share one), each run's first StepHot::run_class set (sim/trace/vertex_runs.cpp).
std::vector<VertexRun> vertex_runs(const Program& p, std::vector<StepHot>& hot);

// Throws TraceError.
Program load_trace_file(const std::string& path, const LoadOptions& options);
// `name` stands for the file name in messages; includes resolve relative to its directory.
Program load_trace_text(const std::string& text, const std::string& name, const LoadOptions& options);

// Parses "NAME=EXPR" (a --set argument); throws TraceError naming `--set`.
std::pair<std::string, std::string> parse_set_argument(const std::string& arg);

std::string buffer_kind_name(BufferKind k);

}  // namespace ffsim::trace
