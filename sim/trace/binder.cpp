#include "sim/trace/binder.h"

namespace ffsim::trace {

ArgSpec Enum(std::string name, std::vector<GLenum> allowed) {
  ArgSpec s;
  s.kind = ArgKind::Enum;
  s.name = std::move(name);
  s.allowed = std::move(allowed);
  return s;
}
ArgSpec Int(std::string name, std::int64_t min, std::int64_t max) {
  ArgSpec s;
  s.kind = ArgKind::Int;
  s.name = std::move(name);
  s.min = min;
  s.max = max;
  return s;
}
ArgSpec Float(std::string name) {
  ArgSpec s;
  s.kind = ArgKind::Float;
  s.name = std::move(name);
  return s;
}
ArgSpec Float32(std::string name) {
  ArgSpec s;
  s.kind = ArgKind::Float32;
  s.name = std::move(name);
  return s;
}
ArgSpec Bool(std::string name) {
  ArgSpec s;
  s.kind = ArgKind::Bool;
  s.name = std::move(name);
  return s;
}
ArgSpec Bitfield(std::string name, std::vector<GLenum> bits) {
  ArgSpec s;
  s.kind = ArgKind::Bitfield;
  s.name = std::move(name);
  s.allowed = std::move(bits);
  return s;
}
ArgSpec ClientImage(std::string name) {
  ArgSpec s;
  s.kind = ArgKind::Image;
  s.name = std::move(name);
  return s;
}
ArgSpec Numbers(std::string name, int count, bool float32) {
  ArgSpec s;
  s.kind = ArgKind::Numbers;
  s.name = std::move(name);
  s.count = count;
  s.float32 = float32;
  return s;
}

std::string CommandDef::signature() const {
  std::string s = name;
  for (const auto& a : args) {
    s.append(" ").append(a.name);
    if (a.kind == ArgKind::Numbers) {
      if (a.count == 0) s.append("...");
      else s.append("[").append(std::to_string(a.count)).append("]");
    }
  }
  return s;
}

CommandDef& CommandTable::add(std::string name, std::vector<ArgSpec> args, CommandFn fn) {
  if (name.empty()) throw BindError("a command needs a name");
  if (defs_.count(name)) throw BindError(name + " is bound twice");
  for (std::size_t k = 0; k < args.size(); ++k)
    if (args[k].kind == ArgKind::Numbers && args[k].count == 0 && k + 1 != args.size())
      throw BindError(name + ": a Numbers argument that takes the rest of the line must be last");
  CommandDef d;
  d.name = name;
  d.args = std::move(args);
  d.call = std::move(fn);
  return defs_.emplace(name, std::move(d)).first->second;
}

const CommandDef* CommandTable::find(const std::string& name) const {
  auto it = defs_.find(name);
  return it == defs_.end() ? nullptr : &it->second;
}

}  // namespace ffsim::trace
