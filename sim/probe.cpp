#include "sim/probe.h"

#include <cstdio>

namespace ffsim {

namespace {
std::string num(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}
}  // namespace

std::string describe_codes(const std::uint16_t* codes, int bits) {
  const double max = static_cast<double>((1u << bits) - 1u);
  std::string c = "codes (", v = " = (";
  for (int k = 0; k < 4; ++k) {
    if (k) {
      c.append(", ");
      v.append(", ");
    }
    c.append(std::to_string(codes[k]));
    v.append(num(codes[k] / max));
  }
  c.append(")").append(v).append(")");
  return c;
}

std::string describe_values(const double* values) {
  std::string v = "values (";
  for (int k = 0; k < 4; ++k) {
    if (k) v.append(", ");
    v.append(num(values[k]));
  }
  v.append(")");
  return v;
}

std::string describe_color(const Framebuffer& fb, int x, int y) {
  const std::size_t i = 4 * fb.index(x, y);
  if (fb.format().float_color()) return describe_values(&fb.values()[i]);
  return describe_codes(&fb.codes()[i], fb.format().color_bits);
}

}  // namespace ffsim
