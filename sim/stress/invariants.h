// The invariants of issue 9, as functions the tests and `ffsim stress` share.
// Each runs one stage chain of the paper on a batch of inputs and returns counts
// (never throws on a violation; the caller decides what is fatal):
//
//   encoding_path  ellipses -> bumpshadow encodings (eq41, eq51, 8-bit maps)
//   combiner_path  ellipses -> T^n codes -> register combiners (paper section 5),
//                  hardware profile against `ideal`, every register traced
//   lookup_path    ellipses -> T^r codes -> colour matrix + alpha colour table
//                  (section 4.1.4), hardware profile against `ideal`
//   field_path     height field -> visibility, ellipse fit, encodings, horizon,
//                  references, at thread counts 1, 2 and 3
//
// The error bounds are derived in docs/numerics.md §12.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "bumpshadow/encodings.h"
#include "bumpshadow/heightfield.h"
#include "pipeline/number/profile.h"
#include "sim/stress/cases.h"

namespace ffsim::stress {

// The paper's range arguments, checked per texel (or per texel and light) before
// each clamp. Violations are not errors: they say where the paper's assumptions
// fail and which clamp then decides the result (numerics §12.4).
struct RangeCounts {
  long long texels = 0;            // ellipses examined
  long long center = 0;            // |C| > 1 (section 4.1's assumption)
  long long tr_component = 0;      // texels with a T1^r/T2^r component outside [-1, 1]
  long long tn_component = 0;      // texels with a T1^n/T2^n component outside [-1, 1]
  long long t3r_alpha = 0;         // rx^2/2 > 1 (rx > sqrt 2): T3^r clamps
  long long t1n_alpha = 0;         // rx^2 > 1: T1^n alpha clamps
  long long cases = 0;             // (texel, light) pairs of the combiner and lookup paths
  long long dot = 0;               // a stage-0 dot product outside [-1, 1] (register clamp)
  long long sum = 0;               // the stage-1 sum outside [-1, 1] or below 0 (register clamp / final max(0, .))
  long long lookup_index = 0;      // A' outside [0, 1]: the table's index clamp
  long long lookup_entry = 0;      // lookup(A') > 1: the clamped table entry
  void add(const RangeCounts& o);
  std::string str() const;  // one line, "name=count" pairs
};

// Result of a hardware-against-ideal path.
struct PathStats {
  long long cases = 0;
  long long clamp_free = 0;       // cases in which no clamp acts (the bound applies)
  long long nonfinite = 0;        // NaN or Inf in a register, an output or an ideal value
  long long out_of_range = 0;     // register outside [-1, 1], output code > max or value outside [0, 1]
  long long bound_exceeded = 0;   // clamp-free cases with |hw - ideal| > bound
  double max_err_lsb = 0;         // max |hw - ideal| over clamp-free cases, in LSB of the hw width
  double max_ratio = 0;           // max |hw - ideal| / bound over clamp-free cases
  double max_err_clamped_lsb = 0; // max |hw - ideal| over clamped cases (no bound; reported)
  std::string worst;              // the clamp-free case with the largest ratio
  std::string violation;          // the first NaN/Inf or out-of-range case
  void add(const PathStats& o);
  bool hard_violation() const { return nonfinite || out_of_range || bound_exceeded; }
};

// numerics §12.2: bound on |alpha_hw - alpha_ideal| (value units) for the section-5
// combiner pass with T^n (unbiased, unquantised) and light (lx, ly), on a fixed
// profile whose texture, colour and combiner grids all equal 1/M.
double combiner_bound(const bumpshadow::Vec3& t1n, const bumpshadow::Vec3& t2n, double lx, double ly, int M);
// numerics §12.3: bound on |lookup_hw - lookup_ideal| (value units) for the
// section 4.1.4 table path, d = L.t of the decoded texel, table width W, result
// stored with `bits` bits.
double lookup_bound(double d, int table_width, int bits);

// Encodings of the ellipses for every light: every value finite, eq41 == eq51 ==
// ellipse_test up to rounding (relative 1e-12 of the terms), the decoded 8-bit maps
// within quantisation_bound41/51 for texels whose components are in range.
struct EncodingStats {
  long long cases = 0, nonfinite = 0, formula_mismatch = 0, bound_exceeded = 0;
  double max_ratio41 = 0, max_ratio51 = 0;  // |decoded - float| / bound (in-range texels)
  std::string worst;
  void add(const EncodingStats& o);
  bool hard_violation() const { return nonfinite || formula_mismatch || bound_exceeded; }
};
EncodingStats encoding_path(const std::vector<bumpshadow::Ellipse>& e, const std::vector<LightDir>& lights,
                            RangeCounts* ranges);

PathStats combiner_path(const std::vector<bumpshadow::Ellipse>& e, const std::vector<LightDir>& lights,
                        const Profile& hw, RangeCounts* ranges);
PathStats lookup_path(const std::vector<bumpshadow::Ellipse>& e, const std::vector<LightDir>& lights,
                      const Profile& hw, int table_width, RangeCounts* ranges);

// Height field through the precomputation. Hard: NaN/Inf, a value outside its
// documented range (radii < 0 or rx > ry, |a| != 1, horizon outside [0, pi/2],
// soft reference outside [0, 1], non-0/1 lit maps), a map that differs between
// thread counts 1, 2 and 3. Flagged (not hard): |C| > 1, rx > sqrt 2.
struct FieldStats {
  long long texels = 0, nonfinite = 0, out_of_range = 0, thread_mismatch = 0;
  long long center_outside = 0, rx_above_sqrt2 = 0;
  double max_abs_center = 0, max_rx = 0;
  std::string detail;  // first violation, if any
  void add(const FieldStats& o);
  bool hard_violation() const { return nonfinite || out_of_range || thread_mismatch; }
};
FieldStats field_path(const bumpshadow::HeightField& hf, const std::vector<LightDir>& lights, int rays,
                      RangeCounts* ranges);

}  // namespace ffsim::stress
