// Internal: atan2(y, x) for finite y >= 0 and x (the corner angles of the signpost triangulation: y is 4 x
// a triangle's area, x the law-of-cosines term of the corner), in [0, pi], within 4 ulp of std::atan2; NaN
// when an argument is not finite.
//
// Hand-written because the corner angles are the largest transcendental cost of iARAP's precompute (two per
// input face, two per flip: 106K calls on beetle's 20K vertices), and glibc's atan2 spends most of its time
// on branches over the ranges of its arguments, which mispredict on mesh data. This one has no branch that
// depends on the data: the argument is reduced to |u| <= tan(pi/8) and atan(u) = u + u^3 Q(u^2) is a
// degree-10 polynomial Q fitted to atan at Chebyshev nodes (relative error 8e-18 in exact arithmetic;
// unit test: UpperHalfAngle.*).
#pragma once

#include "../core/math_constants.h"
#include <algorithm>
#include <cmath>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace iarap::detail {

// 1.0 where a > b, else 0.0 (0.0 when either is NaN), as a compare mask where SSE2 has one: compilers
// turn the plain conditional into a branch.
inline double one_if_greater(double a, double b) {
#if defined(__SSE2__)
  return _mm_cvtsd_f64(_mm_and_pd(_mm_cmpgt_sd(_mm_set_sd(a), _mm_set_sd(b)), _mm_set_sd(1.0)));
#else
  return a > b ? 1.0 : 0.0;
#endif
}

inline double upper_half_angle(double y, double x) {
  constexpr double kTanPiOver8 = 0.41421356237309504880;
  const double ax = std::fabs(x);
  const double lo = std::min(y, ax), hi = std::max(y, ax);
  // atan(lo / hi) in [0, pi/4]; above tan(pi/8) by atan(t) = pi/4 + atan((t - 1) / (t + 1)). Every
  // selection is a product with an exact 0 / 1 or +-1 factor.
  const double reduce = one_if_greater(lo, kTanPiOver8 * hi);
  const double u =
      (lo - reduce * hi) / (hi + reduce * lo + (1.0 - one_if_greater(hi, 0.0))); // 0 / 1 at the origin
  const double s = u * u, s2 = s * s, s4 = s2 * s2, s8 = s4 * s4;
  // Q(s) by Estrin's scheme (shorter dependency chains than Horner's).
  const double q01 = -0.3333333333333333 + 0.19999999999995655 * s;
  const double q23 = -0.14285714284692108 + 0.11111111017148394 * s;
  const double q45 = -0.09090904649365056 + 0.07692184732950036 * s;
  const double q67 = -0.06664531781776156 + 0.05858314940389342 * s;
  const double q89 = -0.050862692605655895 + 0.03925406201134413 * s;
  const double q = (q01 + q23 * s2) + (q45 + q67 * s2) * s4 + (q89 - 0.01920292492757084 * s2) * s8;
  const double a = (u + u * s * q) + reduce * (kPi / 4);
  const double steep = one_if_greater(y, ax); // measured from the y axis: pi/2 - a
  const double b = steep * (kPi / 2) + (1.0 - 2.0 * steep) * a;
  const double left = one_if_greater(0.0, x);                       // x < 0: pi - b
  return left * kPi + (1.0 - 2.0 * left) * b + ((x - x) + (y - y)); // NaN in, NaN out (min / max drop one)
}

} // namespace iarap::detail
