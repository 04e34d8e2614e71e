// Names the runs of quiet vertex-data calls for the vertex-run memo
// (sim/vertex_run_memo.h, docs/performance.md 25.1): runs of equal calls
// (the same commands with the same argument bits) share an id, unique in the
// process, and each id carries how its calls use the current attributes.
#include <atomic>
#include <bit>
#include <unordered_map>

#include "sim/hash.h"
#include "sim/trace/trace.h"

namespace ffsim::trace {

namespace {

// Shorter runs are called: the memo's comparison costs about what a few calls do.
constexpr std::uint16_t kMinMemoRun = 8;

// Ids of every program loaded by this process (64 bits: never reused).
std::atomic<std::uint64_t> next_run_id{1};

std::size_t arg_count(const Program& p, std::size_t k) { return p.steps[k].args.size(); }

bool same_call(const Program& p, const std::vector<StepHot>& hot, std::size_t a, std::size_t b) {
  if (hot[a].def != hot[b].def || arg_count(p, a) != arg_count(p, b)) return false;
  for (std::size_t i = 0; i < arg_count(p, a); ++i) {
    const PackedArg& x = p.packed[hot[a].packed_at + i];
    const PackedArg& y = p.packed[hot[b].packed_at + i];
    if (x.kind != y.kind || x.i != y.i || std::bit_cast<std::uint64_t>(x.f) != std::bit_cast<std::uint64_t>(y.f)) return false;
  }
  return true;
}

std::uint64_t run_hash(const Program& p, const std::vector<StepHot>& hot, std::size_t k, std::size_t n) {
  std::uint64_t h = n;
  for (std::size_t j = k; j < k + n; ++j) {
    hash_mix(h, reinterpret_cast<std::uintptr_t>(hot[j].def));
    for (std::size_t i = 0; i < arg_count(p, j); ++i) {
      const PackedArg& a = p.packed[hot[j].packed_at + i];
      hash_mix(h, static_cast<std::uint64_t>(a.i) ^ (static_cast<std::uint64_t>(a.kind) << 56));
      hash_mix(h, std::bit_cast<std::uint64_t>(a.f));
    }
  }
  return h;
}

// How the run's calls use the attributes; false when a call's effect is not
// described (CommandDef::sets_attribute / makes_vertex): such a run is not memoized.
bool run_usage(const Program& p, const std::vector<StepHot>& hot, std::size_t k, std::size_t n, VertexRunUsage& u) {
  constexpr std::uint8_t kVertexReads = static_cast<std::uint8_t>(~kAttribNormal);  // colours, coordinates
  std::uint8_t read = 0;
  for (std::size_t j = k; j < k + n; ++j) {
    const CommandDef& d = *hot[j].def;
    if (d.makes_vertex) {
      u.has_vertex = true;
      read |= static_cast<std::uint8_t>(kVertexReads & ~u.written);  // (the entry values still current)
    } else if (d.sets_attribute != 0) {
      const std::int64_t unit = d.per_unit ? p.packed[hot[j].packed_at].i - static_cast<std::int64_t>(gl::TEXTURE0) : 0;
      if (unit < 0 || unit >= kClipTexUnits) return false;  // (a quiet run's units are the profile's)
      u.written |= static_cast<std::uint8_t>(d.sets_attribute << unit);
    } else {
      return false;
    }
  }
  u.read_first = read & u.written;
  return true;
}

}  // namespace

std::vector<VertexRun> vertex_runs(const Program& p, std::vector<StepHot>& hot) {
  std::vector<VertexRun> runs;
  std::vector<std::size_t> first_of;  // runs[c]'s first step
  std::unordered_multimap<std::uint64_t, std::uint32_t> by_hash;
  // The runs as the replay loop meets them: from a step with quiet_run >= 2, that many steps.
  for (std::size_t k = 0; k < hot.size();) {
    const std::size_t n = hot[k].quiet_run;
    if (n < 2) {
      ++k;
      continue;
    }
    VertexRunUsage usage;
    if (n >= kMinMemoRun && run_usage(p, hot, k, n, usage)) {
      const std::uint64_t h = run_hash(p, hot, k, n);
      std::uint32_t cls = 0;
      for (auto [it, end] = by_hash.equal_range(h); it != end && cls == 0; ++it) {
        const std::size_t f = first_of[it->second - 1];
        bool same = hot[f].quiet_run == n;
        for (std::size_t j = 0; j < n && same; ++j) same = same_call(p, hot, f + j, k + j);
        if (same) cls = it->second;
      }
      if (cls == 0) {
        runs.push_back({0, usage});
        first_of.push_back(k);
        cls = static_cast<std::uint32_t>(runs.size());
        by_hash.emplace(h, cls);
      }
      hot[k].run_class = cls;
    }
    k += n;
  }
  const std::uint64_t base = next_run_id.fetch_add(runs.size());
  for (std::size_t c = 0; c < runs.size(); ++c) runs[c].id = base + c;
  return runs;
}

}  // namespace ffsim::trace
