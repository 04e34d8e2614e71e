// Helpers shared by the trace subcommands (replay, diff, compare, info): flag
// values, error printing, and the small hand-written JSON output.
#pragma once
#include <iosfwd>
#include <string>
#include <string_view>
#include <vector>

#include "sim/trace/error.h"
#include "sim/trace/trace.h"

namespace ffsim::cli {

// A JSON string literal with quotes, escaping ", \ and control characters.
std::string json_string(std::string_view s);
// A JSON number (shortest round-trip form), or null for NaN and infinities.
std::string json_number(double v);
std::string json_string_array(const std::vector<std::string>& v);

// "A,B" or "AxB" into two integers (exactly two, nothing else).
bool parse_int_pair(const std::string& s, char sep, int& a, int& b);

// Prints `file:line:column: message` and the offending line with a caret; a
// message without a position is prefixed with `ffsim SUBCOMMAND: `.
void print_trace_error(std::ostream& err, const std::string& subcommand, const trace::TraceError& e);

// Flags shared by replay, compare and info: --set, --profile, --size. Returns
// true when args[i] was one of them (advancing i past its value); sets `error`
// for a missing or bad value.
bool parse_load_flag(const std::vector<std::string>& args, std::size_t& i, trace::LoadOptions& opt,
                     std::string& error);

}  // namespace ffsim::cli

#include "sim/image_diff.h"

namespace ffsim::cli {

// One line: "alpha.png: 37 of 4096 pixels differ; max |d| in 8-bit LSB: 2; RMSE ...".
std::string describe_diff(const std::string& name, const ImageDiff& d);
// {"name": ..., "identical": ..., ...}
std::string json_diff(const std::string& name, const ImageDiff& d);
// "diff-<name with / replaced by _>.png" for a heat map of `name`.
std::string heatmap_name(const std::string& name);

}  // namespace ffsim::cli

namespace ffsim::cli {
// Diffs named image pairs, prints the report (text or JSON; `header_json` is
// inserted first into the JSON object), writes heat maps into `out_dir` when it is
// not empty. Returns 0 identical, 1 different, 2 error.
int run_diff(const std::vector<std::pair<std::string, std::pair<const Image*, const Image*>>>& pairs,
             const std::vector<std::string>& only_a, const std::vector<std::string>& only_b, const std::string& out_dir,
             bool json, std::ostream& out, std::ostream& err, const std::string& header_json);
}  // namespace ffsim::cli
