// `ffsim info TRACE`: what a trace declares and does, without running it.
#include <ostream>

#include "sim/cli/cli.h"
#include "sim/cli/trace_cli.h"
#include "sim/trace/expr.h"
#include "sim/trace/generators.h"
#include "sim/trace/trace.h"

namespace ffsim::cli {

namespace {
const char* type_name(SampleType t) {
  switch (t) {
    case SampleType::U8: return "8-bit";
    case SampleType::U16: return "16-bit";
    case SampleType::F32: return "float";
  }
  return "";
}
}  // namespace

Subcommand info_command() {
  Subcommand s;
  s.name = "info";
  s.summary = "show a trace's parameters, resources and passes";
  s.usage =
      "usage: ffsim info TRACE [--set NAME=VALUE ...] [--profile NAME|FILE] [--size WxH]\n"
      "       ffsim info --commands\n\n"
      "Loads a trace without running it and prints its set-up (framebuffer, profile),\n"
      "parameters with defaults, values and descriptions, client images (files,\n"
      "generators, tables), passes (the commands that write the framebuffer) and\n"
      "outputs. Trace errors are reported like `ffsim replay` does; exit code 1.\n"
      "--commands lists the GL commands this build binds, with their arguments (passes\n"
      "marked), and the image generators with their keys.\n";
  s.run = [](const std::vector<std::string>& args, std::ostream& out, std::ostream& err) {
    if (args.size() == 1 && args[0] == "--commands") {
      for (const auto& [name, def] : trace::gl_commands().all())
        out << def.signature() << (def.is_pass ? "    (pass)" : "") << "\n";
      for (const auto& [name, g] : trace::generators().all())
        out << "generate NAME " << name << " " << g.keys << "    " << g.description << "\n";
      return 0;
    }
    trace::LoadOptions lo;
    std::string path, error;
    for (std::size_t i = 0; i < args.size(); ++i) {
      if (parse_load_flag(args, i, lo, error)) {
        if (!error.empty()) return usage_error(err, "info", error);
        continue;
      }
      if (!args[i].empty() && args[i][0] == '-') return usage_error(err, "info", std::string("unknown argument `") + args[i] + "`");
      if (!path.empty()) return usage_error(err, "info", std::string("expected one trace, got a second one `") + args[i] + "`");
      path = args[i];
    }
    if (path.empty()) return usage_error(err, "info", "expected a trace file");
    trace::Program p;
    try {
      p = trace::load_trace_file(path, lo);
    } catch (const trace::TraceError& e) {
      print_trace_error(err, "info", e);
      return 1;
    }
    out << "trace " << path << " (ffsim-trace " << trace::kTraceVersion << ")\n";
    if (p.files.size() > 1) {
      out << "files:";
      for (const auto& f : p.files) out << " " << f;
      out << "\n";
    }
    out << "framebuffer " << p.width << "x" << p.height << ", profile " << p.profile.name << "\n";
    out << "parameters:" << (p.params.empty() ? " none" : "") << "\n";
    for (const auto& q : p.params) {
      out << "  " << q.name << " = " << trace::format_number(q.value);
      if (q.overridden) out << " (default " << trace::format_number(q.default_value) << ")";
      if (!q.description.empty()) out << "  " << q.description;
      out << "\n";
    }
    out << "resources:" << (p.resources.empty() ? " none" : "") << "\n";
    for (const auto& r : p.resources)
      out << "  " << r.name << ": " << r.kind << " " << r.source << ", " << r.image->width << "x" << r.image->height
          << ", " << r.image->channels << " channel" << (r.image->channels == 1 ? "" : "s") << ", "
          << type_name(r.image->type) << "  " << r.where.str() << "\n";
    out << "passes: " << p.pass_count() << "\n";
    int n = 0;
    for (const auto& st : p.steps)
      if (st.is_pass()) out << "  " << ++n << " " << st.name << "  " << st.where.str() << "\n";
    out << "outputs:\n";
    bool any = false;
    for (const auto& st : p.steps) {
      switch (st.kind) {
        case trace::StepKind::Dump:
          out << "  dump " << trace::buffer_kind_name(st.buffer) << " " << st.file << "  " << st.where.str() << "\n";
          any = true;
          break;
        case trace::StepKind::DumpImage:
          out << "  dump image " << st.image.text << " " << st.file << "  " << st.where.str() << "\n";
          any = true;
          break;
        case trace::StepKind::Hash:
          out << "  hash " << trace::buffer_kind_name(st.buffer) << "  " << st.where.str() << "\n";
          any = true;
          break;
        case trace::StepKind::ExpectHash:
        case trace::StepKind::ExpectPixel:
        case trace::StepKind::ExpectImage:
        case trace::StepKind::ExpectError:
        case trace::StepKind::ExpectEnabled:
        {
          std::string t = st.line_text.substr(static_cast<std::size_t>(st.where.column - 1));
          t = t.substr(0, t.find('#'));
          while (!t.empty() && (t.back() == ' ' || t.back() == '\t')) t.pop_back();
          out << "  " << t << "  " << st.where.str() << "\n";
        }
          any = true;
          break;
        case trace::StepKind::Call: break;
      }
    }
    if (!any) out << "  none\n";
    return 0;
  };
  return s;
}

}  // namespace ffsim::cli
