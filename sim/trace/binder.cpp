#include "sim/trace/binder.h"

#include <algorithm>

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

ArgSpec ClientImageOut(std::string name) {
  ArgSpec s;
  s.kind = ArgKind::OutImage;
  s.name = std::move(name);
  return s;
}

const Image& Args::image_at(std::size_t k) const {
  const ArgValue& v = v_.at(k);
  if (v.client_memory && memory_) {
    auto it = memory_->images.find(v.text);
    if (it != memory_->images.end()) return it->second;
  }
  return *v.image;
}

Image& Args::out_image_at(std::size_t k) const {
  const ArgValue& v = v_.at(k);
  if (!memory_) throw std::logic_error(v.text + ": a call writing client memory needs the run's ClientMemory");
  auto it = memory_->images.find(v.text);
  if (it == memory_->images.end()) it = memory_->images.emplace(v.text, *v.image).first;
  return it->second;
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
  auto out_images = std::count_if(args.begin(), args.end(), [](const ArgSpec& a) { return a.kind == ArgKind::OutImage; });
  if (out_images > 1) throw BindError(name + ": at most one OutImage argument");
  CommandDef d;
  d.name = name;
  d.args = std::move(args);
  d.call = std::move(fn);
  return defs_.emplace(name, std::move(d)).first->second;
}

CommandDef& CommandTable::alias(std::string name, const std::string& of) {
  const CommandDef* d = find(of);
  if (!d) throw BindError(name + ": alias of the unbound command " + of);
  if (defs_.count(name)) throw BindError(name + " is bound twice");
  CommandDef copy = *d;
  copy.name = name;
  return defs_.emplace(name, std::move(copy)).first->second;
}

const CommandDef* CommandTable::find(const std::string& name) const {
  auto it = defs_.find(name);
  return it == defs_.end() ? nullptr : &it->second;
}

}  // namespace ffsim::trace
