#include "bumpshadow/detmath.h"

#include <cmath>

namespace ffsim::bumpshadow::det {

namespace {

constexpr double kPio2Hi = 1.57079632673412561417e+00;  // first 33 bits of pi/2
constexpr double kPio2Lo = 6.07710050650619224932e-11;  // pi/2 - kPio2Hi
constexpr double kInvPio2 = 6.36619772367581382433e-01;  // 2/pi

// fdlibm __kernel_sin / __kernel_cos polynomials on [-pi/4, pi/4].
double ksin(double x) {
  constexpr double S1 = -1.66666666666666324348e-01, S2 = 8.33333333332248946124e-03,
                   S3 = -1.98412698298579493134e-04, S4 = 2.75573137070700676789e-06,
                   S5 = -2.50507602534068634195e-08, S6 = 1.58969099521155010221e-10;
  const double z = x * x, v = z * x;
  const double r = S2 + z * (S3 + z * (S4 + z * (S5 + z * S6)));
  return x + v * (S1 + z * r);
}

double kcos(double x) {
  constexpr double C1 = 4.16666666666666019037e-02, C2 = -1.38888888888741095749e-03,
                   C3 = 2.48015872894767294178e-05, C4 = -2.75573143513906633035e-07,
                   C5 = 2.08757232129817482790e-09, C6 = -1.13596475577881948265e-11;
  const double z = x * x;
  const double r = z * (C1 + z * (C2 + z * (C3 + z * (C4 + z * (C5 + z * C6)))));
  const double hz = 0.5 * z, w = 1.0 - hz;
  return w + (((1.0 - w) - hz) + z * r);
}

// x = n pi/2 + r, |r| <= pi/4 (Cody-Waite, two constants; exact enough for |x| <= 1e6).
double reduce(double x, long& n) {
  const double k = std::floor(x * kInvPio2 + 0.5);
  n = static_cast<long>(k);
  return (x - k * kPio2Hi) - k * kPio2Lo;
}

}  // namespace

double sin(double x) {
  long n = 0;
  const double r = reduce(x, n);
  switch (((n % 4) + 4) % 4) {
    case 0: return ksin(r);
    case 1: return kcos(r);
    case 2: return -ksin(r);
    default: return -kcos(r);
  }
}

double cos(double x) {
  long n = 0;
  const double r = reduce(x, n);
  switch (((n % 4) + 4) % 4) {
    case 0: return kcos(r);
    case 1: return -ksin(r);
    case 2: return -kcos(r);
    default: return ksin(r);
  }
}

double tan(double x) { return sin(x) / cos(x); }

// fdlibm s_atan.c.
double atan(double x) {
  constexpr double atanhi[] = {4.63647609000806093515e-01, 7.85398163397448278999e-01, 9.82793723247329054082e-01,
                               1.57079632679489655800e+00};
  constexpr double atanlo[] = {2.26987774529616870924e-17, 3.06161699786838301793e-17, 1.39033110312309984516e-17,
                               6.12323399573676603587e-17};
  constexpr double aT[] = {3.33333333333329318027e-01,  -1.99999999998764832476e-01, 1.42857142725034663711e-01,
                           -1.11111104054623557880e-01, 9.09088713343650656196e-02,  -7.69187620504482999495e-02,
                           6.66107313738753120669e-02,  -5.83357013379057348645e-02, 4.97687799461593236017e-02,
                           -3.65315727442169155270e-02, 1.62858201153657823623e-02};
  if (std::isnan(x)) return x;
  const bool neg = x < 0;
  double a = neg ? -x : x;
  int id;
  if (a < 0.4375) {
    id = -1;
  } else if (a < 0.6875) {
    id = 0;
    a = (2.0 * a - 1.0) / (2.0 + a);
  } else if (a < 1.1875) {
    id = 1;
    a = (a - 1.0) / (a + 1.0);
  } else if (a < 2.4375) {
    id = 2;
    a = (a - 1.5) / (1.0 + 1.5 * a);
  } else {
    id = 3;
    a = -1.0 / a;  // 1/inf = 0 gives pi/2
  }
  const double z = a * a, w = z * z;
  const double s1 = z * (aT[0] + w * (aT[2] + w * (aT[4] + w * (aT[6] + w * (aT[8] + w * aT[10])))));
  const double s2 = w * (aT[1] + w * (aT[3] + w * (aT[5] + w * (aT[7] + w * aT[9]))));
  double r;
  if (id < 0) r = a - a * (s1 + s2);
  else r = atanhi[id] - ((a * (s1 + s2) - atanlo[id]) - a);
  return neg ? -r : r;
}

double atan2(double y, double x) {
  constexpr double pi = 3.14159265358979311600e+00, pio2 = 1.57079632679489655800e+00;
  if (x == 0) return y > 0 ? pio2 : y < 0 ? -pio2 : 0.0;
  if (std::abs(y) <= std::abs(x)) {
    const double a = atan(y / x);
    if (x > 0) return a;
    return y >= 0 ? a + pi : a - pi;
  }
  const double a = atan(x / y);  // |x/y| < 1
  return y > 0 ? pio2 - a : -pio2 - a;
}

double asin(double x) {
  if (x >= 1) return 1.57079632679489655800e+00;
  if (x <= -1) return -1.57079632679489655800e+00;
  return atan2(x, std::sqrt((1.0 - x) * (1.0 + x)));
}

}  // namespace ffsim::bumpshadow::det
