#include "sim/cli/trace_cli.h"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <ostream>

namespace ffsim::cli {

std::string json_string(std::string_view s) {
  std::string o = "\"";
  for (const char ch : s) {
    const auto c = static_cast<unsigned char>(ch);
    switch (ch) {
      case '"': o += "\\\""; break;
      case '\\': o += "\\\\"; break;
      case '\n': o += "\\n"; break;
      case '\r': o += "\\r"; break;
      case '\t': o += "\\t"; break;
      default:
        if (c < 0x20) {
          char buf[8];
          std::snprintf(buf, sizeof buf, "\\u%04x", static_cast<unsigned>(c));
          o += buf;
        } else {
          o += ch;
        }
    }
  }
  return o + "\"";
}

std::string json_number(double v) {
  if (!std::isfinite(v)) return "null";
  char buf[64];
  auto r = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, r.ptr);
}

std::string json_string_array(const std::vector<std::string>& v) {
  std::string o = "[";
  for (std::size_t k = 0; k < v.size(); ++k) {
    if (k) o += ", ";
    o += json_string(v[k]);
  }
  return o + "]";
}

bool parse_int_pair(const std::string& s, char sep, int& a, int& b) {
  const auto p = s.find(sep);
  if (p == std::string::npos) return false;
  const char* end = s.data() + s.size();
  auto r1 = std::from_chars(s.data(), s.data() + p, a);
  if (r1.ec != std::errc() || r1.ptr != s.data() + p || p == 0) return false;
  auto r2 = std::from_chars(s.data() + p + 1, end, b);
  return r2.ec == std::errc() && r2.ptr == end && p + 1 < s.size();
}

void print_trace_error(std::ostream& err, const std::string& subcommand, const trace::TraceError& e) {
  if (e.where().empty()) err << "ffsim " << subcommand << ": ";
  err << e.what() << "\n" << e.excerpt();
}

bool parse_load_flag(const std::vector<std::string>& args, std::size_t& i, trace::LoadOptions& opt,
                     std::string& error) {
  const std::string& a = args[i];
  auto value = [&](const char* what) -> const std::string* {
    if (i + 1 >= args.size()) {
      error = a + " needs " + what;
      return nullptr;
    }
    return &args[++i];
  };
  if (a == "--set") {
    const std::string* v = value("NAME=VALUE");
    if (!v) return true;
    const auto eq = v->find('=');
    if (eq == std::string::npos || eq == 0) {
      error = std::string("--set expects NAME=VALUE, got `") + *v + "`";
      return true;
    }
    opt.sets.emplace_back(v->substr(0, eq), v->substr(eq + 1));
    return true;
  }
  if (a == "--profile") {
    if (const std::string* v = value("a profile name or file")) opt.profile = *v;
    return true;
  }
  if (a == "--size") {
    const std::string* v = value("WxH");
    if (!v) return true;
    int w = 0, h = 0;
    if (!parse_int_pair(*v, 'x', w, h)) error = std::string("--size expects WxH, e.g. 256x256, got `") + *v + "`";
    else opt.size = std::make_pair(w, h);
    return true;
  }
  return false;
}

}  // namespace ffsim::cli

namespace ffsim::cli {

namespace {
std::string fixed(double v, int digits) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", digits, v);
  return buf;
}
std::string channel_names(int channels) {
  switch (channels) {
    case 1: return "V";
    case 2: return "VA";
    case 3: return "RGB";
    default: return "RGBA";
  }
}
}  // namespace

std::string describe_diff(const std::string& name, const ImageDiff& d) {
  using trace::cat;
  std::string s = cat(name, ": ");
  if (!d.same_shape) return cat(s, d.shape_note);
  if (d.identical()) return cat(s, "identical");
  s += cat(std::to_string(d.differing_pixels), " of ", std::to_string(d.total_pixels), " pixels differ; max |d| in ",
           std::to_string(d.lsb_bits), "-bit LSB:");
  const std::string names = channel_names(d.channels);
  for (std::size_t c = 0; c < d.max_lsb.size(); ++c) s += cat(" ", names.substr(c, 1), " ", fixed(d.max_lsb[c], 2));
  s += cat("; RMSE ", fixed(d.rmse, 6), "; PSNR ", fixed(d.psnr, 2), " dB");
  if (d.is_mask) s += cat("; lit/shadow disagreements ", std::to_string(d.lit_shadow_disagreements));
  return s;
}

std::string json_diff(const std::string& name, const ImageDiff& d) {
  using trace::cat;
  std::string s = cat("{\"name\": ", json_string(name), ", \"identical\": ", d.identical() ? "true" : "false",
                      ", \"same_shape\": ", d.same_shape ? "true" : "false");
  if (!d.same_shape) return cat(s, ", \"note\": ", json_string(d.shape_note), "}");
  s += cat(", \"width\": ", std::to_string(d.width), ", \"height\": ", std::to_string(d.height),
           ", \"channels\": ", std::to_string(d.channels), ", \"lsb_bits\": ", std::to_string(d.lsb_bits),
           ", \"max_lsb\": [");
  for (std::size_t c = 0; c < d.max_lsb.size(); ++c) s += cat(c ? ", " : "", json_number(d.max_lsb[c]));
  s += cat("], \"differing_pixels\": ", std::to_string(d.differing_pixels),
           ", \"total_pixels\": ", std::to_string(d.total_pixels), ", \"rmse\": ", json_number(d.rmse),
           ", \"psnr\": ", json_number(d.psnr));
  if (d.is_mask) s += cat(", \"lit_shadow_disagreements\": ", std::to_string(d.lit_shadow_disagreements));
  return cat(s, "}");
}

std::string heatmap_name(const std::string& name) {
  std::string n = name;
  for (auto& c : n)
    if (c == '/' || c == '\\') c = '_';
  const auto dot = n.rfind('.');
  if (dot != std::string::npos && dot > 0) n = n.substr(0, dot);
  return std::string("diff-") + n + ".png";
}

}  // namespace ffsim::cli
