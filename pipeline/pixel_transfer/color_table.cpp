#include "pipeline/pixel_transfer/color_table.h"

#include "pipeline/pixel_transfer/pixel_map.h"

namespace ffsim::pixel {

template <class T>
void set_table_entries(ColorTable& table, const RgbaImage<T>& groups) {
  const int nc = component_count(table.base);
  table.entries.assign(static_cast<std::size_t>(table.width) * nc, 0.0);
  for (int i = 0; i < table.width; ++i) {
    const T* g = groups.at(i, 0);
    for (int k = 0; k < nc; ++k) {
      const int c = rgba_component_for(table.base, k);
      const T prod = g[c] * static_cast<T>(table.scale[c]);
      const T v = prod + static_cast<T>(table.bias[c]);
      table.entries[static_cast<std::size_t>(i) * nc + k] = static_cast<double>(clamp01(v));
    }
  }
}

template <class T>
void color_table_lookup(RgbaImage<T>& img, const ColorTable& table) {
  if (!table_active(table)) return;
  const int nc = component_count(table.base);
  const int w = table.width;
  std::vector<T> e(table.entries.size());
  for (std::size_t i = 0; i < e.size(); ++i) e[i] = static_cast<T>(table.entries[i]);
  // The components the table replaces (Table 3.12), and the table column of each.
  int comp[4], src[4], active = 0;
  for (int c = 0; c < 4; ++c)
    if (const int s = source_component(table.base, c); s >= 0) {
      comp[active] = c;
      src[active++] = s;
    }
  const std::size_t n = img.size();
  for (int a = 0; a < active; ++a) {  // (components are independent: one pass each)
    T* v = img.px.data() + comp[a];
    const T* col = e.data() + src[a];
    for (std::size_t p = 0; p < n; ++p, v += 4) *v = col[static_cast<std::size_t>(table_index(*v, w)) * static_cast<std::size_t>(nc)];
  }
}

template void set_table_entries<float>(ColorTable&, const RgbaImage<float>&);
template void set_table_entries<double>(ColorTable&, const RgbaImage<double>&);
template void color_table_lookup<float>(RgbaImage<float>&, const ColorTable&);
template void color_table_lookup<double>(RgbaImage<double>&, const ColorTable&);

}  // namespace ffsim::pixel
