// Colour-table lookup (GL121 §3.6.5 "Color Table Lookup", Table 3.13; SGI_color_table)
// and colour-table contents (§3.6.3 "Color Table Specification").
#pragma once
#include "pipeline/pixel_transfer/pixel_image.h"
#include "pipeline/pixel_transfer/pixel_state.h"

namespace ffsim::pixel {

// Builds the entries of `table` (its base, width, scale and bias already set)
// from `width` unpacked RGBA groups: each component clamp01(c * scale + bias)
// evaluated in T, then the components of the table's base format are kept
// (L and I from R, GL121 Table 3.15).
template <class T>
void set_table_entries(ColorTable& table, const RgbaImage<T>& groups);

// The lookup: does nothing when the table is disabled or its width is 0.
// Otherwise every component the base format replaces (ALPHA: A; LUMINANCE:
// R,G,B; LUMINANCE_ALPHA: R,G,B,A; INTENSITY: R,G,B,A; RGB: R,G,B; RGBA: all)
// gets its own index floor(clamp01(c) * (W - 1) + 1/2) (in T) and is replaced by
// the matching entry component at that index (L for R, G and B; I for all four).
// Other components pass through unchanged and unclamped.
template <class T>
void color_table_lookup(RgbaImage<T>& img, const ColorTable& table);

inline bool table_active(const ColorTable& t) { return t.enabled && t.width > 0; }

}  // namespace ffsim::pixel
