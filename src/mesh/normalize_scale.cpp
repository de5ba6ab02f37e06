#include "iarap/mesh/normalize_scale.h"

#include <algorithm>
#include <cmath>

namespace iarap {

double normalizing_scale(const Eigen::MatrixXd& V) {
  double largest = 0;
  for (Eigen::Index i = 0; i < V.size(); ++i) {
    const double x = std::abs(V.data()[i]);
    if (std::isfinite(x) && x > largest) largest = x;
  }
  if (largest == 0) return 1;
  int exponent = 0;
  std::frexp(largest, &exponent); // largest = m 2^exponent, m in [0.5, 1)
  // 2^1024 is not a double: near DBL_MAX the coordinates end in [1, 2) instead.
  return std::ldexp(1.0, std::min(exponent, 1023));
}

} // namespace iarap
