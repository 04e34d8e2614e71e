// Deterministic elementary functions for the precomputation. The C library's
// sin, cos, atan ... are not required to be correctly rounded, so their last
// bit may differ between libms; these use only +, -, *, / and sqrt (all
// correctly rounded in IEEE 754, no FMA: -ffp-contract=off) in a fixed order,
// so they return the same bits on every machine. Accuracy: a few ulp (the
// fdlibm kernels and argument reduction, Sun Microsystems 1993, re-typed; tested
// against the C library to 1e-15). docs/numerics.md §11.1.
#pragma once

namespace ffsim::bumpshadow::det {

double sin(double x);   // |x| <= 1e6
double cos(double x);   // |x| <= 1e6
double tan(double x);   // sin / cos
double atan(double x);
double atan2(double y, double x);  // (0, 0) -> 0
double asin(double x);  // |x| <= 1

}  // namespace ffsim::bumpshadow::det
