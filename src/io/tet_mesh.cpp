#include "iarap/io/tet_mesh.h"

#include <Eigen/Geometry>
#include <Eigen/LU>

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <vector>

namespace iarap {

namespace {

// det(b - a, c - a, d - a) / 6 of tetrahedron t.
double signed_volume(const Eigen::MatrixXd& V, const Eigen::MatrixXi& T, Eigen::Index t) {
  const Eigen::Vector3d a = V.row(T(t, 0)).transpose();
  const Eigen::Matrix3d D = (Eigen::Matrix3d() << V.row(T(t, 1)) - a.transpose(),
                             V.row(T(t, 2)) - a.transpose(), V.row(T(t, 3)) - a.transpose())
                                .finished();
  return D.determinant() / 6.0;
}

std::string tet_name(const Eigen::MatrixXi& T, Eigen::Index t) {
  return "tetrahedron " + std::to_string(t) + " (" + std::to_string(T(t, 0)) + ", " +
         std::to_string(T(t, 1)) + ", " + std::to_string(T(t, 2)) + ", " + std::to_string(T(t, 3)) + ")";
}

} // namespace

Eigen::VectorXd tet_signed_volumes(const Eigen::MatrixXd& V, const Eigen::MatrixXi& T) {
  Eigen::VectorXd volume(T.rows());
  for (Eigen::Index t = 0; t < T.rows(); ++t) volume(t) = signed_volume(V, T, t);
  return volume;
}

TetProblem find_tet_problem(const Eigen::MatrixXd& V, const Eigen::MatrixXi& T) {
  for (Eigen::Index t = 0; t < T.rows(); ++t)
    for (int k = 0; k < 4; ++k) {
      if (T(t, k) < 0 || T(t, k) >= V.rows())
        return {t, tet_name(T, t) + " uses vertex " + std::to_string(T(t, k)) + "; the mesh has " +
                       std::to_string(V.rows()) + " vertices"};
      for (int l = 0; l < k; ++l)
        if (T(t, k) == T(t, l))
          return {t, tet_name(T, t) + " uses vertex " + std::to_string(T(t, k)) + " twice"};
    }
  double edge_sum = 0.0;
  for (Eigen::Index t = 0; t < T.rows(); ++t)
    for (int k = 0; k < 4; ++k)
      for (int l = k + 1; l < 4; ++l) edge_sum += (V.row(T(t, k)) - V.row(T(t, l))).norm();
  const double mean_edge = T.rows() > 0 ? edge_sum / (6.0 * static_cast<double>(T.rows())) : 0.0;
  const double tiny = 1e-12 * mean_edge * mean_edge * mean_edge;
  for (Eigen::Index t = 0; t < T.rows(); ++t) {
    const double volume = signed_volume(V, T, t);
    if (!(std::abs(volume) > tiny))
      return {t, tet_name(T, t) + " has zero volume (" + std::to_string(volume) +
                     ", at most 1e-12 x the mean " + "edge length " + std::to_string(mean_edge) + " cubed)"};
  }
  return {};
}

Eigen::MatrixXi tet_boundary_faces(const Eigen::MatrixXi& T) {
  // Outward faces of a positive tetrahedron (a, b, c, d), the one opposite each corner in turn.
  static constexpr int outward[4][3] = {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}};
  struct FaceKey {
    std::array<int, 3> sorted;
    int tet, corner;
  };
  std::vector<FaceKey> keys;
  keys.reserve(static_cast<size_t>(4 * T.rows()));
  for (Eigen::Index t = 0; t < T.rows(); ++t)
    for (int k = 0; k < 4; ++k) {
      std::array<int, 3> f{T(t, outward[k][0]), T(t, outward[k][1]), T(t, outward[k][2])};
      std::sort(f.begin(), f.end());
      keys.push_back({f, static_cast<int>(t), k});
    }
  std::sort(keys.begin(), keys.end(), [](const FaceKey& x, const FaceKey& y) {
    return x.sorted != y.sorted ? x.sorted < y.sorted : x.tet != y.tet ? x.tet < y.tet : x.corner < y.corner;
  });
  std::vector<std::pair<int, int>> boundary; // (tet, corner), in tet order below
  for (size_t i = 0; i < keys.size();) {
    size_t j = i + 1;
    while (j < keys.size() && keys[j].sorted == keys[i].sorted) ++j;
    if (j == i + 1) boundary.emplace_back(keys[i].tet, keys[i].corner);
    i = j;
  }
  std::sort(boundary.begin(), boundary.end());
  Eigen::MatrixXi F(static_cast<Eigen::Index>(boundary.size()), 3);
  for (size_t i = 0; i < boundary.size(); ++i) {
    const auto [t, k] = boundary[i];
    for (int c = 0; c < 3; ++c) F(static_cast<Eigen::Index>(i), c) = T(t, outward[k][c]);
  }
  return F;
}

} // namespace iarap
