// Tetrahedral meshes in the server's session (Session::load_tet_mesh): drawn by their boundary faces,
// deformed by the volumetric energy (arap_tets.h), and the surface-only features refused by name.
#include "../../app/serve/session.h" // the tool's sources: tests/ is on the include path, app/ is not
#include "../solver/tet_fixtures.h"
#include "serve_test_meshes.h"

#include "iarap/io/tet_mesh.h"
#include "iarap/solver/arap.h"
#include "iarap/solver/arap_tets.h"

#include <gtest/gtest.h>

namespace {

using iarap::InputError;
using iarap::serve::Session;
using iarap::serve::SolveProgress;
using iarap::serve::SolveRequest;
using iarap::test::contains;
using iarap::test::rows_of;

// A 6 x 1 x 1 bar of cubes (6 tetrahedra each): its x = 0 end fixed, its x = 6 end the handle.
struct BarSession {
  iarap::test::TetBar bar = iarap::test::tet_bar(6, 1, 1);
  Session session;
  Eigen::VectorXi fixed, handle;
  BarSession() {
    session.load_tet_mesh("bar.mesh", iarap::TetMesh{bar.V, bar.T, {}});
    std::vector<int> f, h;
    for (Eigen::Index v = 0; v < bar.V.rows(); ++v) {
      if (bar.V(v, 0) == 0.0) f.push_back(static_cast<int>(v));
      if (bar.V(v, 0) == 6.0) h.push_back(static_cast<int>(v));
    }
    fixed = Eigen::Map<Eigen::VectorXi>(f.data(), static_cast<Eigen::Index>(f.size()));
    handle = Eigen::Map<Eigen::VectorXi>(h.data(), static_cast<Eigen::Index>(h.size()));
    session.set_constraints(fixed, handle);
  }
  // The handle lifted by `up` in z.
  SolveRequest lift(double up) const {
    SolveRequest request;
    request.solve.max_iterations = 50;
    Eigen::MatrixXd targets = rows_of(bar.V, handle);
    targets.col(2).array() += up;
    request.handle_targets = targets;
    return request;
  }
};

} // namespace

TEST(ServeTetSession, ShownByItsBoundaryAndDeformedByTheVolumeEnergy) {
  BarSession s;
  const auto& summary = s.session.mesh_summary();
  EXPECT_EQ(summary.tetrahedra, 36);
  EXPECT_EQ(summary.vertices, 28); // 7 x 2 x 2, all on the surface of a bar one cube thick
  const Eigen::MatrixXi boundary = iarap::tet_boundary_faces(s.bar.T);
  EXPECT_EQ(summary.faces, boundary.rows()); // 2 triangles per unit square of the surface: 2 (4 x 6 + 2)
  EXPECT_EQ(summary.faces, 52);
  EXPECT_EQ(s.session.faces().size(), static_cast<std::size_t>(3 * boundary.rows()));

  const SolveRequest request = s.lift(1.0);
  SolveProgress progress;
  const iarap::serve::SolveResult result = s.session.solve(request, progress);
  EXPECT_FALSE(result.planar);
  // The same iterates as the library's tetrahedral solve from the rest shape with the same options.
  iarap::ArapData data = iarap::arap_precompute_tets(
      s.bar.V, s.bar.T, (Eigen::VectorXi(s.fixed.size() + s.handle.size()) << s.fixed, s.handle).finished());
  Eigen::MatrixXd targets(s.fixed.size() + s.handle.size(), 3);
  targets << rows_of(s.bar.V, s.fixed), *request.handle_targets;
  Eigen::MatrixXd U = s.bar.V;
  iarap::ArapSolveOptions options = request.solve;
  const iarap::ArapReport report = iarap::arap_solve(data, targets, U, options);
  const Eigen::MatrixXd shown = s.session.snapshot(request.method).V;
  // Same operations in the same order: equal to the rounding of the reductions' thread split, far below
  // 1e-12 of the bar's length.
  EXPECT_LE((shown - U).cwiseAbs().maxCoeff(), 1e-12 * 6);
  EXPECT_EQ(result.report.iterations, report.iterations);
  EXPECT_LE((rows_of(shown, s.handle) - *request.handle_targets).cwiseAbs().maxCoeff(), 1e-12 * 6);
}

TEST(ServeTetSession, SurfaceMethodsAndFeaturesAreRefusedByName) {
  BarSession s;
  SolveProgress progress;
  SolveRequest request = s.lift(0.5);
  request.method = iarap::ArapMethod::Arap;
  try {
    s.session.solve(request, progress);
    FAIL() << "the arap method was accepted on a tetrahedral mesh";
  } catch (const InputError& e) {
    EXPECT_TRUE(contains(e.what(), "method arap: bar.mesh is a tetrahedral mesh")) << e.what();
  }
  request = s.lift(0.5);
  request.cell_energy = true;
  try {
    s.session.solve(request, progress);
    FAIL() << "cell energies were accepted on a tetrahedral mesh";
  } catch (const InputError& e) {
    EXPECT_TRUE(contains(e.what(), "cell_energy (the energy per vertex) works on triangle meshes"))
        << e.what();
  }
  EXPECT_THROW(s.session.intrinsic_overlay(), InputError);
  EXPECT_THROW(s.session.begin_fit(), InputError);
  // A bad tetrahedron is named.
  Session other;
  Eigen::MatrixXi flat(1, 4);
  flat << 0, 1, 2, 2;
  try {
    other.load_tet_mesh("bad.mesh", iarap::TetMesh{s.bar.V, flat, {}});
    FAIL() << "a tetrahedron with a repeated vertex was accepted";
  } catch (const InputError& e) {
    EXPECT_TRUE(contains(e.what(), "bad.mesh: tetrahedron 0")) << e.what();
  }
  EXPECT_FALSE(other.has_mesh());
}
