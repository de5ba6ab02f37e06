#include "iarap/mesh/cotan.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace iarap {

double triangle_area_from_lengths(double a, double b, double c) {
  // Kahan: sort a >= b >= c, then the parenthesization below loses no precision for needles. Sorted by
  // min / max, without branches: swaps on the order of three lengths mispredict about every other face.
  const double high = std::max(a, b), low = std::min(a, b);
  const double largest = std::max(high, c), rest = std::min(high, c);
  const double middle = std::max(low, rest), smallest = std::min(low, rest);
  a = largest;
  b = middle;
  c = smallest;
  const double p = (a + (b + c)) * (c - (a - b)) * (c + (a - b)) * (a + (b - c));
  return 0.25 * std::sqrt(std::max(p, 0.0));
}

namespace {

// cot(alpha) = (b^2 + c^2 - a^2) / (4 * area), alpha the angle opposite side a.
double cotangent_given_four_area(double a, double b, double c, double four_area) {
  return (b * b + c * c - a * a) / four_area;
}

} // namespace

double cotangent_from_lengths(double a, double b, double c) {
  return cotangent_given_four_area(a, b, c, 4.0 * triangle_area_from_lengths(a, b, c));
}

Eigen::MatrixXd face_cotangents(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F) {
  Eigen::MatrixXd C(F.rows(), 3);
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    double l[3];
    for (int k = 0; k < 3; ++k) l[k] = (V.row(F(f, (k + 1) % 3)) - V.row(F(f, (k + 2) % 3))).norm();
    // cotangent_from_lengths per corner, with the face's area computed once (it sorts its arguments, so
    // each corner's call would compute the same bits).
    const double four_area = 4.0 * triangle_area_from_lengths(l[0], l[1], l[2]);
    for (int k = 0; k < 3; ++k)
      C(f, k) = cotangent_given_four_area(l[k], l[(k + 1) % 3], l[(k + 2) % 3], four_area);
  }
  return C;
}

Eigen::SparseMatrix<double> cotan_laplacian(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F) {
  const Eigen::MatrixXd C = face_cotangents(V, F);
  std::vector<Eigen::Triplet<double>> triplets;
  triplets.reserve(static_cast<size_t>(12 * F.rows()));
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    for (int k = 0; k < 3; ++k) {
      const int i = F(f, (k + 1) % 3), j = F(f, (k + 2) % 3);
      const double w = 0.5 * C(f, k); // each face contributes half the cotangent opposite edge (i, j)
      triplets.emplace_back(i, j, -w);
      triplets.emplace_back(j, i, -w);
      triplets.emplace_back(i, i, w);
      triplets.emplace_back(j, j, w);
    }
  }
  Eigen::SparseMatrix<double> L(V.rows(), V.rows());
  L.setFromTriplets(triplets.begin(), triplets.end());
  return L;
}

} // namespace iarap
