#include "bumpshadow/ellipse_test.h"

#include "bumpshadow/reference.h"

namespace ffsim::bumpshadow {

std::vector<double> ellipse_test_map(const EllipseMap& m, const Vec3& light) {
  double lx = 0, ly = 0;
  project_light(light, lx, ly);
  std::vector<double> d(m.ellipse.size());
  for (std::size_t t = 0; t < d.size(); ++t) d[t] = ellipse_test(m.ellipse[t], lx, ly);
  return d;
}

ShadowErrorStats compare_with_reference(const std::vector<double>& d, const std::vector<std::uint8_t>& ref) {
  if (d.size() != ref.size())
    throw HeightFieldError("compare_with_reference: " + std::to_string(d.size()) + " ellipse verdicts vs " +
                           std::to_string(ref.size()) + " reference texels");
  ShadowErrorStats s;
  s.texels = static_cast<long long>(d.size());
  for (std::size_t t = 0; t < d.size(); ++t) {
    const bool e = d[t] >= 0, r = ref[t] != 0;
    s.false_lit += e && !r;
    s.false_shadow += !e && r;
  }
  return s;
}

ShadowErrorStats compare_lit_maps(const std::vector<std::uint8_t>& lit, const std::vector<std::uint8_t>& ref) {
  std::vector<double> d(lit.size());
  for (std::size_t t = 0; t < lit.size(); ++t) d[t] = lit[t] ? 1.0 : -1.0;
  return compare_with_reference(d, ref);
}

}  // namespace ffsim::bumpshadow
