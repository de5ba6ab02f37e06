// lscm against an independent least-squares solve of the conformality equations in complex form (Levy
// et al. 2002, Eq. 5): per triangle sum_j (z_{j+2} - z_{j+1}) U_j = 0, with z_j the corners in a frame of
// the test's own and U_j = u_j + i v_j.
#include "iarap/param/lscm.h"

#include "iarap/core/errors.h"
#include "param/disk_meshes.h"

#include <Eigen/Dense>
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <random>

namespace iarap {
namespace {

using Complex = std::complex<double>;

// Corners of face f as complex numbers in a frame whose first axis is the face's edge from corner 2 to
// corner 0 (not triangle_frames' edge 0 -> 1), so the frames agree with the implementation's only up to
// a rotation, to which the equations are blind.
std::array<Complex, 3> complex_corners(const test::TestMesh& mesh, Eigen::Index f) {
  const Eigen::Vector3d p0 = mesh.V.row(mesh.F(f, 0)), p1 = mesh.V.row(mesh.F(f, 1)),
                        p2 = mesh.V.row(mesh.F(f, 2));
  const Eigen::Vector3d normal = (p1 - p0).cross(p2 - p0).normalized();
  const Eigen::Vector3d x = (p0 - p2).normalized(), y = normal.cross(x);
  std::array<Complex, 3> z;
  const Eigen::Vector3d corners[3] = {p0, p1, p2};
  for (int j = 0; j < 3; ++j) z[j] = Complex((corners[j] - p2).dot(x), (corners[j] - p2).dot(y));
  return z;
}

// Dense least squares: rows 2f, 2f+1 the real and imaginary parts of sum_j W_j U_j / sqrt(area_f) (the
// weight that makes it the energy integrated over the triangle), unknowns (u_0..u_{n-1}, v_0..v_{n-1})
// less the pinned ones, solved by column-pivoting Householder QR.
Eigen::MatrixXd dense_lscm(const test::TestMesh& mesh, const UvPins& pins) {
  const auto n = mesh.V.rows(), nf = mesh.F.rows();
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(2 * nf, 2 * n);
  for (Eigen::Index f = 0; f < nf; ++f) {
    const auto z = complex_corners(mesh, f);
    const double area = 0.5 * std::imag(std::conj(z[1] - z[0]) * (z[2] - z[0]));
    for (int j = 0; j < 3; ++j) {
      const Complex W = (z[(j + 2) % 3] - z[(j + 1) % 3]) / std::sqrt(area);
      const Eigen::Index u = mesh.F(f, j), v = n + mesh.F(f, j);
      // W (u + i v) = (Re W u - Im W v) + i (Im W u + Re W v)
      A(2 * f, u) += W.real();
      A(2 * f, v) -= W.imag();
      A(2 * f + 1, u) += W.imag();
      A(2 * f + 1, v) += W.real();
    }
  }
  std::vector<Eigen::Index> pinned;
  std::vector<double> pinned_values;
  for (int column = 0; column < 2; ++column)
    for (Eigen::Index p = 0; p < pins.size(); ++p) {
      pinned.push_back(column * n + pins.vertices(p));
      pinned_values.push_back(pins.uv(p, column));
    }
  Eigen::VectorXd b = Eigen::VectorXd::Zero(2 * nf);
  std::vector<Eigen::Index> free;
  for (Eigen::Index c = 0; c < 2 * n; ++c) {
    const auto it = std::find(pinned.begin(), pinned.end(), c);
    if (it == pinned.end())
      free.push_back(c);
    else
      b -= A.col(c) * pinned_values[it - pinned.begin()];
  }
  Eigen::MatrixXd A_free(2 * nf, static_cast<Eigen::Index>(free.size()));
  for (std::size_t k = 0; k < free.size(); ++k) A_free.col(static_cast<Eigen::Index>(k)) = A.col(free[k]);
  const Eigen::VectorXd x_free = A_free.colPivHouseholderQr().solve(b);
  Eigen::VectorXd x(2 * n);
  for (std::size_t k = 0; k < free.size(); ++k) x(free[k]) = x_free(static_cast<Eigen::Index>(k));
  for (std::size_t p = 0; p < pinned.size(); ++p) x(pinned[p]) = pinned_values[p];
  Eigen::MatrixXd UV(n, 2);
  UV << x.head(n), x.tail(n);
  return UV;
}

// A spherical cap with every vertex moved at random by up to 5% of the edge length: no symmetry the two
// solves could share by accident, curved so that the conformal energy has a non-zero minimum.
test::TestMesh bumpy_cap() {
  test::TestMesh mesh = test::spherical_cap(4, 11, 1.0);
  std::mt19937 random(3);
  std::uniform_real_distribution<double> offset(-0.01, 0.01);
  for (Eigen::Index v = 0; v < mesh.V.rows(); ++v)
    for (int k = 0; k < 3; ++k) mesh.V(v, k) += offset(random);
  return mesh;
}

TEST(Lscm, MatchesDenseLeastSquaresOfTheConformalityEquations) {
  const test::TestMesh mesh = bumpy_cap();
  const DiskMesh disk = prepare_disk(mesh.V, mesh.F);
  const UvPins pins = lscm_pins(disk);
  const Eigen::MatrixXd UV = lscm(disk, pins);
  const Eigen::MatrixXd reference = dense_lscm(mesh, pins);
  // Both solve a well-conditioned problem of 41 vertices (condition ~1e3): agreement to ~1e-13 of the
  // map's size, checked at 1e-10.
  const double size = pins.uv(1, 0);
  EXPECT_LT((UV - reference).cwiseAbs().maxCoeff(), 1e-10 * size);
  // The pins are held exactly and lie on the boundary, farthest apart.
  EXPECT_EQ(UV.row(pins.vertices(0)), pins.uv.row(0));
  EXPECT_EQ(UV.row(pins.vertices(1)), pins.uv.row(1));
  for (int a : disk.boundary)
    for (int b : disk.boundary) EXPECT_LE((mesh.V.row(a) - mesh.V.row(b)).norm(), size * (1 + 1e-15));
}

TEST(Lscm, MorePinsMatchDenseLeastSquaresToo) {
  // Three pins, one inside, at positions no similarity of the surface meets: the least-squares solution
  // bends to hold them, and both solves agree on it.
  const test::TestMesh mesh = bumpy_cap();
  const DiskMesh disk = prepare_disk(mesh.V, mesh.F);
  UvPins pins;
  pins.vertices.resize(3);
  pins.vertices << disk.boundary[0], disk.boundary[disk.boundary.size() / 2], 0;
  pins.uv.resize(3, 2);
  pins.uv << -1, 0, 1, 0, 0.1, 0.3;
  const Eigen::MatrixXd UV = lscm(disk, pins);
  EXPECT_LT((UV - dense_lscm(mesh, pins)).cwiseAbs().maxCoeff(), 1e-10);
  for (Eigen::Index p = 0; p < 3; ++p) EXPECT_EQ(UV.row(pins.vertices(p)), pins.uv.row(p));
}

TEST(Lscm, FlatMeshMapsBySimilarity) {
  // A planar mesh has a conformal map with zero energy: the identity up to the similarity the pins fix.
  const test::TestMesh mesh = test::flat_disk(3, 9);
  const DiskMesh disk = prepare_disk(mesh.V, mesh.F);
  const UvPins pins = lscm_pins(disk);
  const Eigen::MatrixXd UV = lscm(disk, pins);
  // Distances between the pins are kept (the pins sit at their 3D distance), so the similarity is a rigid
  // motion: every pairwise distance is preserved.
  for (Eigen::Index a = 0; a < mesh.V.rows(); ++a)
    for (Eigen::Index b = 0; b < a; ++b)
      EXPECT_NEAR((UV.row(a) - UV.row(b)).norm(), (mesh.V.row(a) - mesh.V.row(b)).norm(), 1e-12);
}

TEST(Lscm, RefusesBadPins) {
  const test::TestMesh mesh = test::flat_disk(2, 6);
  const DiskMesh disk = prepare_disk(mesh.V, mesh.F);
  UvPins pins = lscm_pins(disk);
  pins.vertices(1) = pins.vertices(0);
  EXPECT_THROW(lscm(disk, pins), InputError);
  pins.vertices(1) = 1000;
  EXPECT_THROW(lscm(disk, pins), InputError);
  pins.vertices(1) = 1;
  pins.uv(1, 1) = NAN;
  EXPECT_THROW(lscm(disk, pins), InputError);
  UvPins one;
  one.vertices = Eigen::VectorXi::Constant(1, 0);
  one.uv = Eigen::MatrixXd::Zero(1, 2);
  EXPECT_THROW(lscm(disk, one), InputError); // the similarity is left free
}

} // namespace
} // namespace iarap
