// The typed-argument binder: how a GL entry point of the Context becomes a trace
// command. Binding a call is one line in the area's file (commands_<area>.cpp):
//
//   t.bind("glClearColor", &Context::clearColor, {Float32("red"), Float32("green"), Float32("blue"), Float32("alpha")});
//   t.bind("glMatrixMode", &Context::matrixMode, {Enum("mode", {gl::MODELVIEW, gl::PROJECTION, gl::TEXTURE, gl::COLOR})});
//   t.bind("glCopyPixels", &Context::copyPixels, {Int("x"), Int("y"), Int("width"), Int("height"), Enum("type")}).pass();
//
// The argument specs say how each trace token is read; the member function's
// parameter types say what the Context receives (checked when the table is built,
// so a mismatch fails every test run, not a user's trace). `.pass()` marks a
// command that writes the framebuffer (a draw or a copy): a pass boundary for
// --dump-each-pass, --explain and --probe. Irregular calls use `add` with a lambda.
#pragma once
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <functional>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "pipeline/gl/enums.h"
#include "sim/context.h"
#include "sim/image_io.h"

namespace ffsim::trace {

enum class ArgKind {
  Enum,      // a GL token by name (GL_MODELVIEW or MODELVIEW) or a number; optional allowed set
  Int,       // an expression with an integral value in [min, max]
  Float,     // an expression, binary64 (GLdouble / GLclampd parameters)
  Float32,   // an expression rounded to binary32 (GLfloat / GLclampf parameters)
  Bool,      // 0, 1, GL_TRUE, GL_FALSE
  Bitfield,  // tokens joined by `|` (GL_COLOR_BUFFER_BIT|GL_STENCIL_BUFFER_BIT) or a number
  Image,     // the name of a client image (`image`, `generate` or `table`)
  Numbers,   // `count` expressions (binary64), or all remaining ones when count is 0
  OutImage,  // the name of client memory the call writes (glReadPixels): declared by the
             // first call naming it, then usable as an image and by `dump image`
};

struct ArgSpec {
  ArgKind kind = ArgKind::Float;
  std::string name;              // the GL parameter name, used in messages
  std::vector<GLenum> allowed;   // Enum: allowed values, Bitfield: allowed bits (empty: any)
  std::int64_t min = std::numeric_limits<std::int32_t>::min();  // Int range
  std::int64_t max = std::numeric_limits<std::int32_t>::max();
  int count = 1;                 // Numbers: how many (0 = one or more, to the end of the line)
  bool float32 = false;          // Numbers: round each to binary32
};

ArgSpec Enum(std::string name, std::vector<GLenum> allowed = {});
ArgSpec Int(std::string name, std::int64_t min = std::numeric_limits<std::int32_t>::min(),
            std::int64_t max = std::numeric_limits<std::int32_t>::max());
ArgSpec Float(std::string name);
ArgSpec Float32(std::string name);
ArgSpec Bool(std::string name);
ArgSpec Bitfield(std::string name, std::vector<GLenum> bits = {});
ArgSpec ClientImage(std::string name);
ArgSpec Numbers(std::string name, int count, bool float32 = false);
ArgSpec ClientImageOut(std::string name);

// One evaluated argument.
struct ArgValue {
  ArgKind kind = ArgKind::Float;
  std::int64_t i = 0;                 // Enum, Int, Bool, Bitfield
  double f = 0;                       // Float, Float32 (already rounded)
  std::vector<double> list;           // Numbers
  std::shared_ptr<const Image> image; // Image (for client memory: its zero-filled initial content)
  bool client_memory = false;         // Image, OutImage: written while the trace runs (glReadPixels)
  std::string text;                   // the token as written (for messages and --explain)
  SourceLoc where;
};

// The scalar part of an argument (kind, integer, float), packed: a program keeps
// these for all its calls in one array (Program::packed), so replaying a call
// reads a few contiguous bytes instead of each ArgValue's own cache line.
struct PackedArg {
  ArgKind kind = ArgKind::Float;
  std::int64_t i = 0;
  double f = 0;
};

// Client memory the GL writes while a trace runs (glReadPixels targets), by image
// name; one per run, so replays of a Program are independent.
struct ClientMemory {
  std::map<std::string, Image> images;
};

class Args {
 public:
  // `packed`: the same arguments' PackedArg, one per element of v (or null).
  explicit Args(const std::vector<ArgValue>& v, ClientMemory* memory = nullptr, const PackedArg* packed = nullptr)
      : v_(v), memory_(memory), packed_(packed) {}
  std::size_t size() const { return v_.size(); }
  const ArgValue& operator[](std::size_t k) const { return v_.at(k); }
  ArgKind kind_at(std::size_t k) const { return packed_ && k < v_.size() ? packed_[k].kind : v_.at(k).kind; }
  GLenum enum_at(std::size_t k) const { return static_cast<GLenum>(int_at(k)); }
  std::int64_t int_at(std::size_t k) const { return packed_ && k < v_.size() ? packed_[k].i : v_.at(k).i; }
  double float_at(std::size_t k) const { return packed_ && k < v_.size() ? packed_[k].f : v_.at(k).f; }
  bool bool_at(std::size_t k) const { return int_at(k) != 0; }
  const std::vector<double>& numbers_at(std::size_t k) const { return v_.at(k).list; }
  // An input image: a file, generated or table image, or client memory written by an
  // earlier call (zeros until then).
  const Image& image_at(std::size_t k) const;
  // The client memory an OutImage argument names (created zero-filled on first use).
  Image& out_image_at(std::size_t k) const;
  const SourceLoc& where_at(std::size_t k) const { return v_.at(k).where; }

 private:
  const std::vector<ArgValue>& v_;
  ClientMemory* memory_;
  const PackedArg* packed_;
};

using CommandFn = std::function<void(Context&, const Args&)>;

// A problem with a call's arguments found when the trace is loaded (beyond each
// argument's kind): the argument it is reported at and the message.
struct ArgProblem {
  std::size_t arg = 0;
  std::string message;
};
using CheckFn = std::function<std::optional<ArgProblem>(const std::vector<ArgValue>&)>;
// The zero-filled client memory an OutImage argument declares, from the call's arguments.
using OutShapeFn = std::function<Image(const std::vector<ArgValue>&)>;

struct CommandDef {
  std::string name;  // "glClearColor"
  std::vector<ArgSpec> args;
  CommandFn call;
  // A bound method whose parameters are all scalars (bool, integers, floating
  // point): the same call straight from the step's packed arguments, without
  // std::function and Args (the replay's vertex data is tens of thousands of such
  // calls per frame; docs/performance.md 16). `method` holds the member function
  // pointer it calls. Null for every other command: `call` then.
  using PackedFn = void (*)(Context&, const PackedArg*, const void* method);
  PackedFn packed_call = nullptr;
  alignas(std::max_align_t) unsigned char method[2 * sizeof(void*)]{};
  bool is_pass = false;  // writes the framebuffer: a pass boundary
  bool explained = false;  // not a pass, but --explain reports after it (texture uploads)
  // glBegin, glEnd and the vertex-data calls between them: they change no state a
  // draw reads, so a deferred draw (Context::set_defer_draws) may stay pending
  // across them; before any other step the executor flushes it.
  bool vertex_data = false;
  // A vertex-data call that never records a GL error (`never_errs`), or only
  // when its first argument is not a texture unit of the profile
  // (`errs_on_unit`: glMultiTexCoord). The replay runs consecutive ones
  // without the per-step bookkeeping (StepHot::quiet_run).
  bool never_errs = false, errs_on_unit = false;
  // What a vertex-data call does to the current attributes, for the vertex-run
  // memo (sim/vertex_run_memo.h): the VertexAttribBit it sets (with
  // `per_unit`, the texture coordinates of the unit its first argument names),
  // or whether it makes a vertex.
  std::uint8_t sets_attribute = 0;
  bool per_unit = false, makes_vertex = false;
  CheckFn check;         // optional load-time check of the evaluated arguments
  OutShapeFn out_shape;  // required when an argument is an OutImage
  CommandDef& pass_boundary() { is_pass = true; return *this; }
  CommandDef& pass() { return pass_boundary(); }
  CommandDef& checked(CheckFn f) { check = std::move(f); return *this; }
  CommandDef& explain_after() { explained = true; return *this; }
  CommandDef& vertex_data_call() { vertex_data = true; return *this; }
  CommandDef& quiet() { never_errs = true; return *this; }
  CommandDef& quiet_with_unit() { errs_on_unit = true; return *this; }
  CommandDef& sets(std::uint8_t attribute) { sets_attribute = attribute; return *this; }
  CommandDef& sets_unit_coordinates() { sets_attribute = kAttribTexCoord0; per_unit = true; return *this; }
  CommandDef& vertex() { makes_vertex = true; return *this; }
  CommandDef& writes_image(OutShapeFn f) { out_shape = std::move(f); return *this; }
  std::string signature() const;  // "glClearColor red green blue alpha"
};

namespace detail {
template <class P>
constexpr bool accepts(ArgKind k) {
  using T = std::remove_cvref_t<P>;
  if constexpr (std::is_same_v<T, bool>) return k == ArgKind::Bool;
  else if constexpr (std::is_floating_point_v<T>) return k == ArgKind::Float || k == ArgKind::Float32 || k == ArgKind::Int;
  else if constexpr (std::is_integral_v<T>) return k == ArgKind::Enum || k == ArgKind::Int || k == ArgKind::Bitfield || k == ArgKind::Bool;
  else if constexpr (std::is_same_v<T, const double*>) return k == ArgKind::Numbers;
  else if constexpr (std::is_same_v<T, std::vector<double>>) return k == ArgKind::Numbers;
  else if constexpr (std::is_same_v<T, Image>) return k == ArgKind::Image;
  else return false;
}
template <class P>
decltype(auto) convert(const Args& a, std::size_t k) {
  using T = std::remove_cvref_t<P>;
  if constexpr (std::is_same_v<T, bool>) return a.int_at(k) != 0;
  else if constexpr (std::is_floating_point_v<T>) return static_cast<T>(a.kind_at(k) == ArgKind::Int ? static_cast<double>(a.int_at(k)) : a.float_at(k));
  else if constexpr (std::is_integral_v<T>) return static_cast<T>(a.int_at(k));
  else if constexpr (std::is_same_v<T, const double*>) return static_cast<const double*>(a[k].list.data());
  else if constexpr (std::is_same_v<T, std::vector<double>>) return static_cast<const std::vector<double>&>(a[k].list);
  else return static_cast<const Image&>(*a[k].image);
}
// convert's conversions of a scalar parameter, from a packed argument.
template <class P>
auto convert_packed(const PackedArg& a) {
  using T = std::remove_cvref_t<P>;
  if constexpr (std::is_same_v<T, bool>) return a.i != 0;
  else if constexpr (std::is_floating_point_v<T>) return static_cast<T>(a.kind == ArgKind::Int ? static_cast<double>(a.i) : a.f);
  else return static_cast<T>(a.i);
}
}  // namespace detail

// Thrown while building a table when a binding is inconsistent (a programming
// error in a commands_*.cpp file; the trace tests build the table and fail).
struct BindError : std::logic_error {
  using std::logic_error::logic_error;
};

class CommandTable {
 public:
  // A lambda command: `fn` reads the arguments through Args.
  CommandDef& add(std::string name, std::vector<ArgSpec> args, CommandFn fn);

  // A Context member bound argument by argument (return value ignored).
  template <class R, class... P>
  CommandDef& bind(std::string name, R (Context::*fn)(P...), std::vector<ArgSpec> args) {
    if (args.size() != sizeof...(P))
      throw BindError(name + ": " + std::to_string(args.size()) + " argument specs for a method with " +
                      std::to_string(sizeof...(P)) + " parameters");
    check_kinds<P...>(name, args);
    CommandDef& d = add(std::move(name), std::move(args), [fn](Context& c, const Args& a) {
      call(c, fn, a, std::index_sequence_for<P...>{});
    });
    if constexpr ((std::is_arithmetic_v<std::remove_cvref_t<P>> && ...)) {
      using Fn = R (Context::*)(P...);
      static_assert(sizeof(Fn) <= sizeof(d.method));
      std::memcpy(d.method, &fn, sizeof fn);
      d.packed_call = [](Context& c, const PackedArg* a, const void* method) {
        Fn f;
        std::memcpy(&f, method, sizeof f);
        call_packed(c, f, a, std::index_sequence_for<P...>{});
      };
    }
    return d;
  }

  // Another name for a bound command (an extension's entry point, glActiveTextureARB).
  CommandDef& alias(std::string name, const std::string& of);

  const CommandDef* find(const std::string& name) const;
  const std::map<std::string, CommandDef>& all() const { return defs_; }

 private:
  template <class... P>
  static void check_kinds(const std::string& name, const std::vector<ArgSpec>& args) {
    using Accepts = bool (*)(ArgKind);
    const Accepts accepts[] = {nullptr, &detail::accepts<P>...};
    for (std::size_t k = 0; k < sizeof...(P) && k < args.size(); ++k)
      if (!accepts[k + 1](args[k].kind))
        throw BindError(name + ": argument " + std::to_string(k + 1) + " (" + args[k].name +
                        ") has a spec kind the method parameter cannot take");
  }
  template <class R, class... P, std::size_t... I>
  static void call(Context& c, R (Context::*fn)(P...), const Args& a, std::index_sequence<I...>) {
    (c.*fn)(detail::convert<P>(a, I)...);
  }
  template <class R, class... P, std::size_t... I>
  static void call_packed(Context& c, R (Context::*fn)(P...), [[maybe_unused]] const PackedArg* a, std::index_sequence<I...>) {
    (c.*fn)(detail::convert_packed<P>(a[I])...);
  }

  std::map<std::string, CommandDef> defs_;
};

// Every bound GL command of this build (sim/trace/commands.cpp lists the areas).
const CommandTable& gl_commands();

// Per-area registration functions (sim/trace/commands_<area>.cpp), called by
// gl_commands(); each area declares its own below its marker.
void register_core_commands(CommandTable& t);
// ==== [issue 3] pixel transfer and pixel rectangles ====
void register_pixels_commands(CommandTable& t);

// ==== [issue 4a] geometry, rasterization, texturing ====
void register_draw_commands(CommandTable& t);

// ==== [issue 4b] per-fragment operations ====
void register_fragment_commands(CommandTable& t);

// ==== [issue 5] register combiners ====
void register_combiners_commands(CommandTable& t);


}  // namespace ffsim::trace
