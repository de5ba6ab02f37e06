// Tests of the lumped mass matrices: totals equal the surface area, known cells on a regular grid,
// intrinsic == extrinsic on Delaunay meshes.
#include "iarap/core/errors.h"
#include "iarap/io/read_mesh.h"
#include "iarap/laplacian/mass_matrix.h"
#include "intrinsic/mesh_generators.h"
#include "test_support.h"

#include <Eigen/Geometry>
#include <gtest/gtest.h>

namespace iarap {
namespace {

double surface_area(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F) {
  double area = 0;
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    const Eigen::Vector3d a = V.row(F(f, 0)), b = V.row(F(f, 1)), c = V.row(F(f, 2));
    area += 0.5 * (b - a).cross(c - a).norm();
  }
  return area;
}

// Both lumpings partition every triangle (Voronoi: circumcentric cells or the obtuse split), so the
// masses sum to the surface area; the intrinsic triangulation has the same total area (no mollification
// on these meshes). Relative round-off 1e-12 for sums of a few thousand positive terms.
TEST(MassMatrix, TotalsEqualSurfaceAreaOnBunny) {
  const MeshData bunny = read_mesh(test::data_path("bunny.off"));
  const IntrinsicDelaunay idt = intrinsic_delaunay(bunny.V, bunny.F);
  ASSERT_EQ(idt.triangulation.mollify_delta, 0.0);
  const double area = surface_area(bunny.V, bunny.F);
  for (MassKind kind : {MassKind::Barycentric, MassKind::Voronoi})
    for (bool intrinsic : {false, true}) {
      const Eigen::SparseMatrix<double> M = mass_matrix(bunny.V, bunny.F, kind, intrinsic, &idt);
      ASSERT_EQ(M.nonZeros(), bunny.V.rows());
      EXPECT_NEAR(Eigen::VectorXd(M.diagonal()).sum(), area, 1e-12 * area)
          << static_cast<int>(kind) << intrinsic;
      // Intrinsic Delaunay triangles have circumcentric cells of positive area at every vertex.
      if (intrinsic) {
        EXPECT_GT(Eigen::VectorXd(M.diagonal()).minCoeff(), 0.0);
      }
    }
}

// Regular grid of spacing h: an interior vertex's Voronoi cell is the h x h square (right triangles, the
// obtuse rule does not apply), its barycentric cell 6 triangles / 3 = h^2 too; intrinsic == extrinsic.
TEST(MassMatrix, RegularGridCells) {
  const int n = 8;
  const test::TestMesh m = test::planar_grid(n);
  const double h = 1.0 / n;
  const int centre = (n / 2) * (n + 1) + n / 2;
  for (MassKind kind : {MassKind::Barycentric, MassKind::Voronoi}) {
    const Eigen::SparseMatrix<double> M = mass_matrix(m.V, m.F, kind);
    EXPECT_NEAR(M.coeff(centre, centre), h * h, 1e-14);
    const Eigen::SparseMatrix<double> M_intrinsic = mass_matrix(m.V, m.F, kind, true);
    EXPECT_LE(Eigen::VectorXd(M.diagonal() - M_intrinsic.diagonal()).cwiseAbs().maxCoeff(), 1e-15);
  }
  // Corner (0, 0) with its single right-angled triangle: Voronoi gives it half the triangle, h^2 / 4.
  EXPECT_NEAR(mass_matrix(m.V, m.F, MassKind::Voronoi).coeff(0, 0), h * h / 4, 1e-15);
}

// An obtuse triangle: Meyer et al. give half its area to the obtuse corner and a quarter to the others.
TEST(MassMatrix, VoronoiObtuseSplit) {
  Eigen::MatrixXd V(3, 3);
  V << 0, 0, 0, 4, 0, 0, 2, 0.5, 0;
  Eigen::MatrixXi F(1, 3);
  F << 0, 1, 2;
  const Eigen::SparseMatrix<double> M = mass_matrix(V, F, MassKind::Voronoi);
  EXPECT_NEAR(M.coeff(2, 2), 0.5, 1e-15);
  EXPECT_NEAR(M.coeff(0, 0), 0.25, 1e-15);
  EXPECT_NEAR(M.coeff(1, 1), 0.25, 1e-15);
}

TEST(MassMatrix, BadFaceIndexNamesTheFace) {
  Eigen::MatrixXd V = Eigen::MatrixXd::Zero(3, 3);
  Eigen::MatrixXi F(1, 3);
  F << 0, 1, 7;
  try {
    mass_matrix(V, F, MassKind::Barycentric);
    FAIL() << "no exception";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("face 0 uses vertex 7"), std::string::npos) << e.what();
  }
}

// The names Python uses map to the (kind, intrinsic) pairs above, each name round-trips in the listed
// order, and an unknown word is refused with the valid ones named.
TEST(MassMatrix, NamedKinds) {
  const std::vector<std::pair<MassKind, bool>> expected = {
      {MassKind::Voronoi, false}, {MassKind::Barycentric, false}, {MassKind::Voronoi, true}};
  ASSERT_EQ(mass_kind_names().size(), expected.size());
  for (std::size_t k = 0; k < expected.size(); ++k) {
    const MassMatrixChoice choice = parse_mass_kind(mass_kind_names()[k]);
    EXPECT_EQ(choice.kind, expected[k].first) << mass_kind_names()[k];
    EXPECT_EQ(choice.intrinsic, expected[k].second) << mass_kind_names()[k];
  }
  try {
    parse_mass_kind("lumped");
    FAIL() << "no exception";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("'lumped'; expected voronoi, barycentric or intrinsic"),
              std::string::npos)
        << e.what();
  }
}

// On the bunny (976 non-Delaunay edges) the intrinsic cells differ from the extrinsic ones at the flipped
// edges' vertices, by a few percent of a cell, while both partition the same total area (first test).
TEST(MassMatrix, IntrinsicCellsDifferWhereEdgesFlip) {
  const MeshData bunny = read_mesh(test::data_path("bunny.off"));
  const Eigen::VectorXd extrinsic = mass_matrix(bunny.V, bunny.F, MassKind::Voronoi).diagonal();
  const Eigen::VectorXd intrinsic = mass_matrix(bunny.V, bunny.F, MassKind::Voronoi, true).diagonal();
  const Eigen::VectorXd relative = (intrinsic - extrinsic).cwiseAbs().cwiseQuotient(extrinsic);
  EXPECT_GT(relative.maxCoeff(), 1e-3);
  EXPECT_LT((relative.array() > 1e-12).count(), bunny.V.rows()); // vertices away from flips keep their cell
}

} // namespace
} // namespace iarap
