#include "sim/trace/executor.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <ostream>

#include "pipeline/gl/enum_names.h"
#include "sim/hash.h"
#include "sim/image_io.h"
#include "sim/trace/explain.h"
#include "sim/trace/expr.h"

namespace ffsim::trace {

namespace fs = std::filesystem;

namespace {

Image buffer_image(const Framebuffer& fb, BufferKind k) {
  switch (k) {
    case BufferKind::Color: return color_image(fb);
    case BufferKind::Alpha: return alpha_image(fb);
    case BufferKind::Stencil: return stencil_image(fb);
    case BufferKind::Depth: return depth_image(fb);
  }
  return color_image(fb);
}

std::string list(const std::vector<double>& v) {
  std::string s = v.size() > 1 ? "(" : "";
  for (std::size_t k = 0; k < v.size(); ++k) s += std::string(k ? ", " : "") + format_number(v[k]);
  return s + (v.size() > 1 ? ")" : "");
}

class Runner {
 public:
  Runner(const Program& p, const RunOptions& o, std::ostream& out) : p_(p), o_(o), out_(out) {}

  RunResult run() {
    try {
      Context ctx(p_.profile, p_.width, p_.height);
      return run_on(ctx);
    } catch (const std::exception& e) {
      r_.ok = false;
      r_.fatal = e.what();
      return std::move(r_);
    }
  }

  RunResult run_on(Context& ctx) {
    const auto t0 = std::chrono::steady_clock::now();
    try {
      ctx.set_threads(o_.threads);
      if (o_.probe) ctx.probe().set_target(o_.probe->first, o_.probe->second);
      // Strips of one state drawn as one batch with threads (Context::set_defer_draws):
      // the pending draw is flushed before every step that is not vertex data.
      ctx.set_defer_draws(o_.threads > 1 && !o_.probe && !o_.explain && !o_.dump_each_pass);
      // The loop reads each step's StepHot (32 bytes, contiguous); the 384-byte
      // Step only where a call needs more than its packed scalar arguments, or
      // for a message (docs/performance.md 16).
      std::vector<StepHot> own;  // (a Program not made by the loader)
      std::vector<VertexRun> own_runs;
      if (p_.hot.size() != p_.steps.size()) {
        own = hot_steps(p_);
        own_runs = vertex_runs(p_, own);
      }
      const std::vector<StepHot>& hot = own.empty() ? p_.hot : own;
      const std::vector<VertexRun>& runs = own.empty() ? p_.vertex_runs : own_runs;
      // Quiet runs (StepHot::quiet_run) cannot record an error on a Context with
      // at least the program's texture units.
      const bool quiet_runs = ctx.profile().texture_units >= p_.profile.texture_units;
      for (std::size_t k = 0; k < p_.steps.size() && r_.ok; ++k) {
        const StepHot& h = hot[k];
        if (h.quiet_run >= 2 && quiet_runs) {
          // The steps one after the other, with what the loop below does for
          // them: nothing to flush (vertex data), the errors of the step before
          // reported first, none of their own, each counted.
          flush_errors();
          if (!r_.ok) break;
          const std::size_t n = h.quiet_run;
          ctx.set_call_site_ref(p_.steps[k + n - 1].where);  // (where the per-step loop leaves it)
          // A run of a class (StepHot::run_class) is replayed from the vertex-run
          // memo when its state allows (Context::vertex_run_replay).
          const VertexRun* run = h.run_class != 0 && h.run_class <= runs.size() ? &runs[h.run_class - 1] : nullptr;
          if (!run || !ctx.vertex_run_replay(run->id, run->usage)) {
            for (const StepHot* q = &h; q != &h + n; ++q) q->packed_call(ctx, p_.packed.data() + q->packed_at, q->def->method);
            if (run) ctx.vertex_run_record(run->id);
          }
          r_.steps += static_cast<int>(n);
          k += n - 1;
          collect_errors(ctx);
          continue;
        }
        const Step& s = p_.steps[k];
        if (!(h.kind == StepKind::Call && h.vertex_data)) ctx.flush_deferred();
        if (h.kind != StepKind::ExpectError) flush_errors();
        if (!r_.ok) break;
        if (!o_.outputs && h.kind != StepKind::Call && h.kind != StepKind::ExpectError) continue;
        ctx.set_call_site_ref(s.where);  // p_.steps outlives the run (the address only: s is not read)
        if (h.packed_call && (h.def->is_pass || !(o_.explain && h.def->explained))) {
          // execute's Call, without the Step: a pass (each glEnd) reads it only
          // to print (after_pass), so the loop touches no cold Step per pass
          // (docs/performance.md 40).
          h.packed_call(ctx, p_.packed.data() + h.packed_at, h.def->method);
          if (h.def->is_pass) after_pass(ctx, s);
        } else {
          execute(ctx, s);
        }
        ++r_.steps;
        collect_errors(ctx);
      }
      ctx.set_defer_draws(false);  // draws what is pending
      flush_errors();
      if (r_.ok && o_.outputs) {
        const Framebuffer& fb = ctx.framebuffer();
        r_.final_hashes.emplace_back("color", hash_hex(buffer_hash(fb, BufferKind::Color)));
        r_.final_hashes.emplace_back("alpha", hash_hex(buffer_hash(fb, BufferKind::Alpha)));
        if (fb.has_stencil()) r_.final_hashes.emplace_back("stencil", hash_hex(buffer_hash(fb, BufferKind::Stencil)));
        if (fb.has_depth()) r_.final_hashes.emplace_back("depth", hash_hex(buffer_hash(fb, BufferKind::Depth)));
        if (o_.keep_images) {
          r_.images["final-color"] = color_image(fb);
          r_.images["final-alpha"] = alpha_image(fb);
        }
      }
    } catch (const std::exception& e) {
      r_.ok = false;
      r_.fatal = e.what();
      try {  // the Context back to immediate draws, with what was pending drawn
        ctx.set_defer_draws(false);
      } catch (const std::exception&) {  // (already failing: the first error is reported)
      }
    }
    commit();
    r_.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return std::move(r_);
  }

 private:
  void execute(Context& ctx, const Step& s) {
    const Framebuffer& fb = ctx.framebuffer();
    switch (s.kind) {
      case StepKind::Call: {
        const PackedArg* packed = p_.packed_args(s);
        if (s.def->packed_call && packed) s.def->packed_call(ctx, packed, s.def->method);
        else s.def->call(ctx, Args(s.args, &memory_, packed));
        if (s.is_pass()) after_pass(ctx, s);
        else if (o_.explain && s.def->explained) explain_call(ctx, s);
        break;
      }
      case StepKind::Dump: {
        Image im = buffer_image(fb, s.buffer);
        write(s.file, im);
        if (o_.keep_images) r_.images[s.file] = std::move(im);
        break;
      }
      case StepKind::DumpImage: {
        const std::vector<ArgValue> one{s.image};
        Image im = Args(one, &memory_).image_at(0);
        write(s.file, im);
        if (o_.keep_images) r_.images[s.file] = std::move(im);
        break;
      }
      case StepKind::Hash:
        r_.hashes.push_back({s.where, s.buffer, hash_hex(buffer_hash(fb, s.buffer))});
        break;
      case StepKind::ExpectHash: {
        const std::uint64_t h = buffer_hash(fb, s.buffer);
        if (h != s.hash)
          fail(s, std::string("expect hash ") + buffer_kind_name(s.buffer) + ": got " + hash_hex(h) + ", expected " + hash_hex(s.hash));
        break;
      }
      case StepKind::ExpectPixel: {
        std::vector<double> got;
        switch (s.buffer) {
          case BufferKind::Color:
            for (int c = 0; c < 4; ++c) got.push_back(fb.color_value(s.x, s.y, c));
            break;
          case BufferKind::Alpha: got.push_back(fb.color_value(s.x, s.y, 3)); break;
          case BufferKind::Stencil: got.push_back(fb.stencil()[fb.index(s.x, s.y)]); break;
          case BufferKind::Depth:
            got.push_back(static_cast<double>(fb.depth()[fb.index(s.x, s.y)]) / fb.depth_max());
            break;
        }
        bool ok = true;
        for (std::size_t c = 0; c < got.size(); ++c) ok = ok && std::fabs(got[c] - s.values[c]) <= s.tol;
        if (!ok)
          fail(s, std::string("expect pixel ") + std::to_string(s.x) + " " + std::to_string(s.y) + " " +
                      buffer_kind_name(s.buffer) + ": got " + list(got) + ", expected " + list(s.values) +
                      std::string(" (tol ") + format_number(s.tol) + ")");
        break;
      }
      case StepKind::ExpectImage: {
        const std::vector<ArgValue> one{s.image};
        const Image& im = Args(one, &memory_).image_at(0);
        std::vector<double> got;
        for (int c = 0; c < im.channels; ++c) got.push_back(im.value(s.x, s.y, c));
        bool ok = true;
        for (std::size_t c = 0; c < got.size(); ++c) ok = ok && std::fabs(got[c] - s.values[c]) <= s.tol;
        if (!ok)
          fail(s, std::string("expect image ") + s.image.text + " " + std::to_string(s.x) + " " + std::to_string(s.y) + ": got " +
                      list(got) + ", expected " + list(s.values) + std::string(" (tol ") + format_number(s.tol) + ")");
        break;
      }
      case StepKind::ExpectEnabled: {
        const bool on = ctx.isEnabled(s.error);  // glIsEnabled
        if (on != s.enabled)
          fail(s, std::string("expect enabled ") + gl::enum_name(s.error) + ": glIsEnabled returned " + (on ? "GL_TRUE" : "GL_FALSE"));
        break;
      }
      case StepKind::ExpectError: {
        const GLenum e = ctx.getError();
        if (e == s.error) {
          pending_.clear();  // the errors were expected
        } else {
          // Error codes share values with other tokens (0 is also GL_FALSE, GL_ZERO).
          auto name = [](GLenum v) { return v == gl::NO_ERROR ? std::string("GL_NO_ERROR") : gl::enum_name(v); };
          fail(s, std::string("expect error ") + name(s.error) + ": glGetError returned " + name(e));
        }
        break;
      }
    }
  }

  void fail(const Step& s, const std::string& m) { r_.expect_failures.push_back(s.where.str() + ": " + m); }

  void collect_errors(const Context& ctx) {
    const auto& log = ctx.error_log();
    for (; seen_errors_ < log.size(); ++seen_errors_) pending_.push_back(log[seen_errors_].str());
  }

  void flush_errors() {
    if (pending_.empty()) return;
    if (o_.strict && r_.ok) {
      r_.ok = false;
      r_.fatal = pending_.front() + " (--strict)";
      r_.strict_stop = true;
      pending_.resize(1);  // later errors of the same step are not reported twice
    }
    for (auto& e : pending_) r_.gl_errors.push_back(std::move(e));
    pending_.clear();
  }

  void after_pass(Context& ctx, const Step& s) {
    ++r_.passes;
    auto records = ctx.probe().take();
    if (o_.explain || (o_.probe && !records.empty())) {
      out_ << "pass " << r_.passes << ": " << s.name << " at " << s.where.str() << "\n";
      if (o_.explain) print_explainers(ctx, PassInfo{r_.passes, s, true});
      for (const auto& rec : records)
        out_ << "  probe (" << o_.probe->first << ", " << o_.probe->second << ") " << rec.stage << ": " << rec.text << "\n";
    }
    if (o_.dump_each_pass) {
      char prefix[64];
      std::snprintf(prefix, sizeof prefix, "passes/%03d-", r_.passes);
      const Framebuffer& fb = ctx.framebuffer();
      const std::string ext = fb.format().float_color() ? ".exr" : ".png";
      write(prefix + s.name + "-color" + ext, color_image(fb));
      write(prefix + s.name + "-alpha" + ext, alpha_image(fb));
      if (fb.has_stencil()) write(prefix + s.name + "-stencil.png", stencil_image(fb));
    }
  }

  void print_explainers(Context& ctx, const PassInfo& info) {
    for (const auto& e : explainers().all()) {
      const std::string text = e.explain(ctx, info);
      std::size_t pos = 0;
      while (pos < text.size()) {
        std::size_t nl = text.find('\n', pos);
        if (nl == std::string::npos) nl = text.size();
        out_ << "  " << e.area << ": " << text.substr(pos, nl - pos) << "\n";
        pos = nl + 1;
      }
    }
  }

  // A call that is not a pass but says what it did (a texture upload's transfer plan).
  void explain_call(Context& ctx, const Step& s) {
    out_ << "call: " << s.name << " at " << s.where.str() << " (not a pass)\n";
    print_explainers(ctx, PassInfo{r_.passes, s, false});
  }

  void write(const std::string& rel, const Image& im) {
    if (o_.out_dir.empty()) return;
    const fs::path final_path = fs::path(o_.out_dir) / rel;
    fs::create_directories(final_path.parent_path());
    // The temporary keeps the extension so write_image picks the same format.
    const fs::path tmp = final_path.parent_path() / (std::string(".ffsim-tmp-") + final_path.filename().string());
    temps_.push_back({tmp, final_path});
    write_image(tmp.string(), im);
    r_.written.push_back(rel);
  }

  void commit() {
    std::error_code ec;
    if (!r_.ok) {
      for (const auto& t : temps_) fs::remove(t.first, ec);
      r_.written.clear();
      return;
    }
    for (const auto& t : temps_) {
      fs::rename(t.first, t.second, ec);
      if (ec && r_.ok) {
        r_.ok = false;
        r_.fatal = std::string("cannot write ") + t.second.string() + ": " + ec.message();
      }
    }
    if (!r_.ok) {
      for (const auto& t : temps_) {
        fs::remove(t.first, ec);
        fs::remove(t.second, ec);
      }
      r_.written.clear();
    }
  }

  const Program& p_;
  const RunOptions& o_;
  std::ostream& out_;
  RunResult r_;
  std::size_t seen_errors_ = 0;
  std::vector<std::string> pending_;
  std::vector<std::pair<fs::path, fs::path>> temps_;
  ClientMemory memory_;  // glReadPixels targets of this run
};

}  // namespace

RunResult run_program(const Program& program, const RunOptions& options, std::ostream& out) {
  return Runner(program, options, out).run();
}

RunResult run_program_on(Context& ctx, const Program& program, const RunOptions& options, std::ostream& out) {
  return Runner(program, options, out).run_on(ctx);
}

}  // namespace ffsim::trace
