// planar_cells: on a planar mesh the per-vertex energies with 2x2 rotations equal the 3D solver's energies
// (arap_energy, 3x3 rotations) of the same map embedded at z = 0; and the per-vertex parameterizations are
// flip-free and exact where an exact answer exists.
#include "iarap/param/planar_cells.h"

#include "iarap/param/arap_parameterize.h"
#include "iarap/solver/arap.h"
#include "param/disk_meshes.h"

#include <Eigen/LU>
#include <gtest/gtest.h>

#include <cmath>

namespace iarap {
namespace {

// A planar grid, made non-Delaunay by random flips (negative cotan weights: iARAP's intrinsic
// triangulation differs from the input), and a smooth map of it close to the identity.
struct PlanarCase {
  test::TestMesh mesh;
  Eigen::MatrixXd UV;
};

// flips = 0 keeps the grid Delaunay (every cotan weight >= 0, the diagonals' 0 to rounding).
PlanarCase planar_case(int flips) {
  PlanarCase c;
  c.mesh = test::planar_grid(7, flips == 0 ? 0.0 : 0.2);
  if (flips > 0) test::random_planar_flips(c.mesh, flips);
  c.UV = c.mesh.V.leftCols(2);
  for (Eigen::Index v = 0; v < c.UV.rows(); ++v) {
    const double x = c.mesh.V(v, 0), y = c.mesh.V(v, 1);
    c.UV.row(v) += 0.03 * Eigen::RowVector2d(std::sin(3 * y), std::cos(2 * x) * x);
  }
  return c;
}

// The 2D energy equals the 3D one when every cell's best 3x3 rotation keeps z (no cell prefers a
// reflection in the plane, which a 3D rotation about an in-plane axis provides): true for a map this close
// to the identity. Both sum the same terms in different orders and frames: agreement to ~1e-15 relative.
void expect_matches_3d(ArapMethod method, const PlanarCells& cells, const PlanarCase& c) {
  ArapOptions options;
  options.method = method;
  options.intrinsic.refine_boundary = false;
  const ArapData data = arap_precompute(c.mesh.V, c.mesh.F, Eigen::VectorXi::Constant(1, 0), options);
  Eigen::MatrixXd U3 = Eigen::MatrixXd::Zero(c.UV.rows(), 3);
  U3.leftCols(2) = c.UV;
  const double planar = planar_cell_energy(cells, c.UV), spatial = arap_energy(data, U3);
  EXPECT_GT(planar, 1e-6); // the map is not rigid
  EXPECT_NEAR(planar, spatial, 1e-12 * spatial) << arap_method_name(method);
}

TEST(PlanarCells, OriginalArapEqualsThe3dEnergyOfAPlanarMap) {
  // On a Delaunay mesh: with negative weights a cell can lower its energy below 0 by rotating away from
  // its rest (the energy is not bounded below, the paper's point), and the 3x3 rotations have more room to
  // do so than the 2x2 ones, so the two minima differ there.
  const PlanarCase c = planar_case(0);
  expect_matches_3d(ArapMethod::Arap,
                    planar_cells(c.mesh.V, c.mesh.F, arap_edge_elements(c.mesh.V, c.mesh.F)), c);
}

TEST(PlanarCells, IarapEqualsThe3dEnergyOfAPlanarMap) {
  const PlanarCase c = planar_case(25); // intrinsic Delaunay: every weight > 0 whatever the input
  IntrinsicOptions options;
  options.refine_boundary = false;
  const PlanarCells cells = planar_cells(
      c.mesh.V, c.mesh.F, iarap_elements(c.mesh.V, intrinsic_delaunay(c.mesh.V, c.mesh.F, options)));
  expect_matches_3d(ArapMethod::Iarap, cells, c);
}

TEST(PlanarCells, FlatCellsKeepTheRestVectors) {
  // On a planar mesh every tangent plane is the plane: s_ec is s_hat_e in a rotated frame, so lengths and
  // the angles between the elements of a cell are kept exactly (to rounding), and the identity has energy 0
  // (to the rounding of the weights of the grid's diagonals, 0 up to 1e-16).
  const PlanarCase c = planar_case(0);
  const PlanarCells cells = planar_cells(c.mesh.V, c.mesh.F, arap_edge_elements(c.mesh.V, c.mesh.F));
  for (Eigen::Index e = 0; e < cells.elements.size(); ++e)
    for (int k = cells.elements.cell_start[static_cast<std::size_t>(e)];
         k < cells.elements.cell_start[static_cast<std::size_t>(e) + 1]; ++k)
      EXPECT_NEAR(cells.s.row(k).norm(), cells.elements.s_hat.row(e).norm(), 1e-15);
  EXPECT_NEAR(planar_cell_energy(cells, c.mesh.V.leftCols(2)), 0, 1e-15);
}

TEST(PlanarCells, PerVertexParameterizationsAreFlipFree) {
  // The cap of most of the sphere where the per-triangle plain iteration folds the rim
  // (arap_parameterize_test): both per-vertex energies stay injective with the defaults.
  const test::TestMesh sphere = test::spherical_cap(8, 24, 0.9 * M_PI);
  for (ParamEnergy energy : {ParamEnergy::Arap, ParamEnergy::Iarap}) {
    ParamOptions options;
    options.energy = energy;
    options.solve.max_iterations = 300;
    const ParamResult result = arap_parameterize(sphere.V, sphere.F, options);
    EXPECT_EQ(result.report.energy, energy);
    EXPECT_EQ(result.report.distortion.flipped, 0) << param_energy_name(energy);
    EXPECT_GT(result.report.distortion.min_det_J, 0) << param_energy_name(energy);
    ASSERT_FALSE(result.report.solve.energies.empty());
    EXPECT_LT(result.report.solve.energies.back(), result.report.solve.initial_energy)
        << param_energy_name(energy);
  }
}

TEST(PlanarCells, IarapFlattensAPlanarNonDelaunayMeshExactly) {
  // A planar mesh has a zero-energy map, the identity, for every energy; iARAP finds it from LSCM (a
  // similarity) although the mesh has negative cotan weights.
  const PlanarCase c = planar_case(25);
  ParamOptions options;
  options.energy = ParamEnergy::Iarap;
  options.solve.tolerance = 0;
  options.solve.max_iterations = 200;
  const ParamResult result = arap_parameterize(c.mesh.V, c.mesh.F, options);
  EXPECT_LT(result.report.solve.energies.back(), 1e-20);
  EXPECT_LT(result.report.distortion.energy, 1e-20);
}

} // namespace
} // namespace iarap
