#include "soft_terms.h"

#include "iarap/core/errors.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace iarap::detail {

namespace {

void check_weight(double W, const std::string& what) {
  if (!(std::isfinite(W) && W > 0))
    throw InputError("ARAP: " + what + " has weight " + std::to_string(W) +
                     "; a soft weight must be finite and > 0");
}

void check_face_point(int face, const Eigen::RowVector3d& B, const Eigen::MatrixXi& F,
                      const std::string& what) {
  if (face < 0 || face >= F.rows())
    throw InputError("ARAP: " + what + " is out of range; mesh has " + std::to_string(F.rows()) + " faces");
  if (!B.allFinite()) throw InputError("ARAP: " + what + " has non-finite barycentric coordinates");
  if (std::abs(B.sum() - 1.0) > 1e-9)
    throw InputError("ARAP: " + what + " has barycentric coordinates summing to " + std::to_string(B.sum()) +
                     ", not 1 (within 1e-9)");
}

} // namespace

void check_soft_constraints(const ArapSoftConstraints& soft, int n, const Eigen::MatrixXi& F,
                            const Eigen::VectorXi& fixed) {
  if (soft.vertex_weights.size() != soft.vertices.size())
    throw InputError("ARAP: soft constraints have " + std::to_string(soft.vertices.size()) +
                     " vertices but " + std::to_string(soft.vertex_weights.size()) + " vertex weights");
  if (soft.face_weights.size() != soft.faces.size() || soft.barycentric.rows() != soft.faces.size() ||
      (soft.faces.size() > 0 && soft.barycentric.cols() != 3))
    throw InputError("ARAP: soft constraints have " + std::to_string(soft.faces.size()) + " faces, " +
                     std::to_string(soft.barycentric.rows()) + " x " +
                     std::to_string(soft.barycentric.cols()) +
                     " barycentric coordinates (want #faces x 3) and " +
                     std::to_string(soft.face_weights.size()) + " face weights");
  std::vector<char> is_fixed(static_cast<size_t>(n), 0);
  for (Eigen::Index k = 0; k < fixed.size(); ++k)
    if (fixed(k) >= 0 && fixed(k) < n) is_fixed[static_cast<size_t>(fixed(k))] = 1;
  for (Eigen::Index k = 0; k < soft.vertices.size(); ++k) {
    const std::string what = "soft vertex [" + std::to_string(k) + "] = " + std::to_string(soft.vertices(k));
    const int v = soft.vertices(k);
    if (v < 0 || v >= n)
      throw InputError("ARAP: " + what + " is out of range; mesh has " + std::to_string(n) + " vertices");
    if (is_fixed[static_cast<size_t>(v)])
      throw InputError("ARAP: " + what + " is also a fixed (hard) vertex; give it one kind of constraint");
    check_weight(soft.vertex_weights(k), what);
  }
  for (Eigen::Index k = 0; k < soft.faces.size(); ++k) {
    const std::string what =
        "soft face point [" + std::to_string(k) + "] on face " + std::to_string(soft.faces(k));
    check_face_point(soft.faces(k), soft.barycentric.row(k), F, what);
    check_weight(soft.face_weights(k), what);
  }
  if (soft.hard_barycentric.rows() != soft.hard_faces.size() ||
      (soft.hard_faces.size() > 0 && soft.hard_barycentric.cols() != 3))
    throw InputError("ARAP: hard point constraints have " + std::to_string(soft.hard_faces.size()) +
                     " faces and " + std::to_string(soft.hard_barycentric.rows()) + " x " +
                     std::to_string(soft.hard_barycentric.cols()) +
                     " barycentric coordinates (want #faces x 3)");
  for (Eigen::Index k = 0; k < soft.hard_faces.size(); ++k)
    check_face_point(soft.hard_faces(k), soft.hard_barycentric.row(k), F,
                     "hard face point [" + std::to_string(k) + "] on face " +
                         std::to_string(soft.hard_faces(k)));
}

std::vector<SoftPoint> soft_points(const ArapSoftConstraints& soft, const Eigen::MatrixXi& F) {
  std::vector<SoftPoint> points;
  points.reserve(static_cast<size_t>(soft.size()));
  for (Eigen::Index k = 0; k < soft.vertices.size(); ++k) {
    const int v = soft.vertices(k);
    points.push_back({{v, v, v}, {1.0, 0.0, 0.0}, soft.vertex_weights(k)});
  }
  for (Eigen::Index k = 0; k < soft.faces.size(); ++k) {
    const int f = soft.faces(k);
    points.push_back({{F(f, 0), F(f, 1), F(f, 2)},
                      {soft.barycentric(k, 0), soft.barycentric(k, 1), soft.barycentric(k, 2)},
                      soft.face_weights(k)});
  }
  for (Eigen::Index k = 0; k < soft.hard_faces.size(); ++k) {
    const int f = soft.hard_faces(k);
    points.push_back({{F(f, 0), F(f, 1), F(f, 2)},
                      {soft.hard_barycentric(k, 0), soft.hard_barycentric(k, 1), soft.hard_barycentric(k, 2)},
                      kHardPointWeight});
  }
  return points;
}

Eigen::SparseMatrix<double> soft_system_matrix(const std::vector<SoftPoint>& points, int n) {
  if (points.empty()) return {};
  std::vector<Eigen::Triplet<double>> triplets;
  triplets.reserve(9 * points.size());
  for (const SoftPoint& p : points)
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) triplets.emplace_back(p.v[i], p.v[j], 2.0 * p.W * p.c[i] * p.c[j]);
  Eigen::SparseMatrix<double> Q(n, n);
  Q.setFromTriplets(triplets.begin(), triplets.end());
  return Q;
}

Eigen::SparseMatrix<double> with_soft(const Eigen::SparseMatrix<double>& L,
                                      const Eigen::SparseMatrix<double>& Q) {
  if (Q.rows() == 0) return L;
  Eigen::SparseMatrix<double> A = L + Q;
  A.makeCompressed();
  return A;
}

double soft_penalty(const std::vector<SoftPoint>& points, const Eigen::MatrixXd& targets, const double* U,
                    const std::vector<int>* row_of, size_t count) {
  double P = 0.0;
  for (size_t k = 0; k < std::min(count, points.size()); ++k) {
    const SoftPoint& p = points[k];
    double d[3] = {-targets(static_cast<Eigen::Index>(k), 0), -targets(static_cast<Eigen::Index>(k), 1),
                   -targets(static_cast<Eigen::Index>(k), 2)};
    for (int j = 0; j < 3; ++j) {
      const int row = row_of ? (*row_of)[static_cast<size_t>(p.v[j])] : p.v[j];
      for (int a = 0; a < 3; ++a) d[a] += p.c[j] * U[3 * row + a];
    }
    P += p.W * (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
  }
  return P;
}

} // namespace iarap::detail
