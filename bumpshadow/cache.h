// On-disk cache of the expensive precomputations (docs/bumpshadow.md §8).
//
// Key: FNV-1a 64 over a format tag, the height field's content hash (size,
// border, every height bit) and the canonical text of every option that changes
// the result (describe_options; the thread count and progress callback do not).
// File: DIR/ellipse-<16 hex>.bin or DIR/horizon-<16 hex>.bin, plain binary,
// little-endian: magic "FFSIMBS1", kind byte, key (u64), then the payload. A
// file that is missing, truncated or has another key is recomputed and rewritten
// (written to a temporary name, then renamed, so readers never see half a file).
#pragma once
#include <cstdint>
#include <string>

#include "bumpshadow/horizon.h"
#include "bumpshadow/shadow_map.h"

namespace ffsim::bumpshadow {

std::uint64_t ellipse_map_key(const HeightField& hf, const ShadowMapOptions& o);
std::uint64_t horizon_map_key(const HeightField& hf, int azimuths, const MarchOptions& m);

// hit (optional) tells whether the result came from the cache.
EllipseMap cached_ellipse_map(const HeightField& hf, const ShadowMapOptions& o, const std::string& dir,
                              bool* hit = nullptr);
HorizonMap cached_horizon_map(const HeightField& hf, int azimuths, const MarchOptions& m, const std::string& dir,
                              int threads = 0, const Progress& progress = {}, bool* hit = nullptr);

}  // namespace ffsim::bumpshadow
