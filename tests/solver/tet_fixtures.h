// Tetrahedral meshes built in code for the tet ARAP tests: a bar of cubes, each split into 6 tetrahedra
// around its main diagonal (Kuhn's subdivision, conforming across cubes), all positive.
#pragma once
#include "iarap/io/tet_mesh.h"

#include <Eigen/Core>

#include <algorithm>
#include <array>
#include <vector>

namespace iarap::test {

struct TetBar {
  Eigen::MatrixXd V; // (nx + 1)(ny + 1)(nz + 1) x 3, cube side h, x fastest
  Eigen::MatrixXi T; // 6 nx ny nz x 4
  int nx, ny, nz;
  int vertex(int i, int j, int k) const { return i + (nx + 1) * (j + (ny + 1) * k); }
};

inline TetBar tet_bar(int nx, int ny, int nz, double h = 1.0) {
  TetBar bar{Eigen::MatrixXd((nx + 1) * (ny + 1) * (nz + 1), 3), Eigen::MatrixXi(6 * nx * ny * nz, 4), nx, ny,
             nz};
  for (int k = 0; k <= nz; ++k)
    for (int j = 0; j <= ny; ++j)
      for (int i = 0; i <= nx; ++i) bar.V.row(bar.vertex(i, j, k)) << i * h, j * h, k * h;
  int t = 0;
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        std::array<int, 3> axes{0, 1, 2};
        do { // the path 000 -> e_a -> e_a + e_b -> 111 along the axes' order
          std::array<int, 3> at{i, j, k};
          int corner[4];
          corner[0] = bar.vertex(at[0], at[1], at[2]);
          for (int s = 0; s < 3; ++s) {
            ++at[static_cast<size_t>(axes[static_cast<size_t>(s)])];
            corner[s + 1] = bar.vertex(at[0], at[1], at[2]);
          }
          bar.T.row(t++) << corner[0], corner[1], corner[2], corner[3];
        } while (std::next_permutation(axes.begin(), axes.end()));
      }
  const Eigen::VectorXd volume = tet_signed_volumes(bar.V, bar.T);
  for (Eigen::Index r = 0; r < bar.T.rows(); ++r)
    if (volume(r) < 0) std::swap(bar.T(r, 2), bar.T(r, 3));
  return bar;
}

} // namespace iarap::test
