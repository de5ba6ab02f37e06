// arap_parameterize: exact flattening of a developable sheet, isometry of a planar mesh, a case where the
// plain iteration flips triangles and the default does not, the circular boundary, scale invariance, and
// the options it refuses.
#include "iarap/param/arap_parameterize.h"

#include "iarap/core/errors.h"
#include "iarap/io/read_mesh.h"
#include "iarap/param/disk_mesh.h"
#include "iarap/param/fixed_boundary_map.h"
#include "param/disk_meshes.h"
#include "test_support.h"

#include <Eigen/LU>
#include <gtest/gtest.h>

#include <cmath>

namespace iarap {
namespace {

// Most of the unit sphere: the cap within 0.9 pi of the pole. Flattening it squeezes the rim; the plain
// local/global iteration folds 24 of its 384 triangles over there (measured), so the test checks that
// it flips some and that the default flips none.
test::TestMesh nearly_closed_sphere() {
  return test::spherical_cap(8, 24, 0.9 * M_PI);
}

TEST(ArapParameterize, RolledUpSheetFlattensExactly) {
  // The quarter cylinder is made of flat rectangles (two rulings each), so the polyhedral surface is
  // developable: an isometric flattening exists and has energy 0. LSCM finds it up to scale, the first
  // global step restores the scale; what remains is rounding, ~1e-16 per unit area per triangle.
  const test::TestMesh sheet = test::quarter_cylinder(12);
  const ParamResult result = arap_parameterize(sheet.V, sheet.F);
  const double area = 0.5 * M_PI; // the rectangles' total area is a bit less; an upper bound suffices
  EXPECT_LT(result.report.distortion.energy, 1e-12 * area);
  EXPECT_EQ(result.report.distortion.flipped, 0);
  EXPECT_TRUE(result.report.solve.converged);
  // The flattening keeps every edge length.
  for (Eigen::Index f = 0; f < sheet.F.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int a = sheet.F(f, k), b = sheet.F(f, (k + 1) % 3);
      EXPECT_NEAR((result.UV.row(a) - result.UV.row(b)).norm(), (sheet.V.row(a) - sheet.V.row(b)).norm(),
                  1e-9);
    }
}

TEST(ArapParameterize, PlainIterationFlipsWhereTheDefaultDoesNot) {
  const test::TestMesh sphere = nearly_closed_sphere();
  ParamOptions plain;
  plain.allow_flips = true;
  const ParamResult flipping = arap_parameterize(sphere.V, sphere.F, plain);
  ASSERT_GT(flipping.report.distortion.flipped, 0) << "the case no longer makes the plain iteration flip";
  EXPECT_LT(flipping.report.distortion.min_det_J, 0);

  const ParamResult flip_free = arap_parameterize(sphere.V, sphere.F);
  EXPECT_EQ(flip_free.report.init_flipped, 0);
  EXPECT_EQ(flip_free.report.distortion.flipped, 0);
  EXPECT_GT(flip_free.report.distortion.min_det_J, 0);
  // Every triangle keeps its orientation at every iterate, not just at the end: det J > 0 along each
  // step is what the line search guarantees, and the final map is checked triangle by triangle here.
  const TriangleFrames frames = triangle_frames(sphere.V, sphere.F);
  for (Eigen::Index f = 0; f < sphere.F.rows(); ++f)
    EXPECT_GT(face_jacobian(frames, sphere.F, flip_free.UV, f).determinant(), 0) << "face " << f;
  // Keeping the rim unfolded costs energy, but little: within 1% of the folded minimum here.
  EXPECT_GE(flip_free.report.distortion.energy, flipping.report.distortion.energy * (1 - 1e-9));
  EXPECT_LT(flip_free.report.distortion.energy, 1.01 * flipping.report.distortion.energy);
}

TEST(ArapParameterize, PlainIterationNeverIncreasesTheEnergy) {
  // E(U + d) <= E(U + d; R) <= E(U; R) = E(U): the local step minimizes over R, the global step over U.
  const test::TestMesh sphere = nearly_closed_sphere();
  ParamOptions plain;
  plain.allow_flips = true;
  plain.solve.accelerator = ArapAccelerator::None;
  plain.solve.tolerance = 0;
  plain.solve.max_iterations = 30;
  const ArapReport report = arap_parameterize(sphere.V, sphere.F, plain).report.solve;
  ASSERT_EQ(report.energies.size(), 30u);
  double previous = report.initial_energy;
  for (double e : report.energies) {
    EXPECT_LE(e, previous * (1 + 1e-12));
    previous = e;
  }
}

// Each accelerator of the engine, with and without flips: the energies never increase (every accepted
// iterate lowers the minimized energy: Anderson's safeguard, the line search, the trust region), and the
// limit is the plain iteration's (a local minimum of the same energy: equal to 1e-4 relative, the spread
// runs stopped by a 1e-9 relative decrease leave), in fewer iterations. Flip-free, every one stays so.
TEST(ArapParameterize, EveryAcceleratorReachesThePlainIterationsMinimum) {
  const test::TestMesh sphere = nearly_closed_sphere();
  for (bool allow_flips : {true, false}) {
    ParamOptions plain;
    plain.allow_flips = allow_flips;
    plain.solve.accelerator = ArapAccelerator::None;
    plain.solve.tolerance = 1e-9;
    plain.solve.max_iterations = 3000;
    const ParamReport a = arap_parameterize(sphere.V, sphere.F, plain).report;
    ASSERT_TRUE(a.solve.converged) << allow_flips;
    for (ArapAccelerator accelerator :
         {ArapAccelerator::Anderson, ArapAccelerator::Lbfgs, ArapAccelerator::Newton}) {
      const std::string what =
          arap_accelerator_name(accelerator) + (allow_flips ? " with flips" : " flip-free");
      ParamOptions options = plain;
      options.solve.accelerator = accelerator;
      const ParamReport b = arap_parameterize(sphere.V, sphere.F, options).report;
      ASSERT_TRUE(b.solve.converged) << what;
      EXPECT_EQ(b.solve.accelerator, accelerator) << what;
      EXPECT_LT(b.solve.iterations, a.solve.iterations) << what;
      EXPECT_NEAR(b.distortion.energy, a.distortion.energy, 1e-4 * a.distortion.energy) << what;
      double previous = b.solve.initial_energy;
      for (double e : b.solve.energies) {
        EXPECT_LE(e, previous * (1 + 1e-12)) << what;
        previous = e;
      }
      if (!allow_flips) {
        EXPECT_EQ(b.distortion.flipped, 0) << what;
      }
    }
  }
}

TEST(ArapParameterize, StopsOnTheEnginesRules) {
  const test::TestMesh sphere = nearly_closed_sphere();
  ParamOptions options;
  options.solve.tolerance = -1; // the energy rule off: only the gradient rule can stop it
  options.solve.gradient_tolerance = 1e-6;
  options.solve.max_iterations = 1000;
  const ArapReport gradient = arap_parameterize(sphere.V, sphere.F, options).report.solve;
  EXPECT_EQ(gradient.stop_reason, ArapStopReason::GradientTolerance);
  EXPECT_LE(gradient.gradient_norms.back(), 1e-6 * gradient.initial_gradient_norm);

  options.solve.gradient_tolerance = 0;
  options.solve.accelerator = ArapAccelerator::None;
  options.solve.time_budget_ms = 1e-3; // the first iteration ends past it
  const ArapReport budget = arap_parameterize(sphere.V, sphere.F, options).report.solve;
  EXPECT_EQ(budget.stop_reason, ArapStopReason::TimeBudget);
  EXPECT_EQ(budget.iterations, 1);
}

TEST(ArapParameterize, FlippedInitialMapFallsBackToTutte) {
  // A saddle steep enough that LSCM folds triangles at the centre (8, measured): the flip-free iteration
  // starts from Tutte's map instead and stays injective.
  const test::TestMesh saddle = test::polar_mesh(6, 16, 0, [](double r, double a) {
    return Eigen::Vector3d(r * std::cos(a), r * std::sin(a), 2 * r * r * std::cos(3 * a));
  });
  const ParamResult result = arap_parameterize(saddle.V, saddle.F);
  ASSERT_GT(result.report.init_flipped, 0) << "LSCM no longer flips on this saddle";
  EXPECT_TRUE(result.report.init_fallback);
  EXPECT_EQ(result.report.init, ParamInit::Tutte);
  EXPECT_EQ(result.report.distortion.flipped, 0);
}

TEST(ArapParameterize, PlanarMeshMapsIsometrically) {
  // A flat disk is its own best map: the result is a rigid motion of (x, y), energy ~0.
  const test::TestMesh disk = test::flat_disk(5, 14);
  for (ParamInit init : {ParamInit::Lscm, ParamInit::Tutte, ParamInit::Harmonic}) {
    ParamOptions options;
    options.init = init;
    options.solve.tolerance = 0;
    options.solve.max_iterations = 300;
    const ParamResult result = arap_parameterize(disk.V, disk.F, options);
    EXPECT_LT(result.report.distortion.energy, 1e-12) << param_init_name(init);
    const Eigen::Index a = 0, b = disk.V.rows() - 1;
    EXPECT_NEAR((result.UV.row(a) - result.UV.row(b)).norm(), (disk.V.row(a) - disk.V.row(b)).norm(), 1e-6);
  }
}

TEST(ArapParameterize, CircularBoundaryStaysOnTheCircle) {
  const test::TestMesh cap = test::spherical_cap(6, 18, 0.4 * M_PI);
  ParamOptions options;
  options.boundary = ParamBoundary::Circle;
  options.init = ParamInit::Harmonic;
  const ParamResult result = arap_parameterize(cap.V, cap.F, options);
  const DiskMesh disk = prepare_disk(cap.V, cap.F);
  const Eigen::MatrixXd circle = circle_boundary(disk);
  for (std::size_t p = 0; p < disk.boundary.size(); ++p)
    EXPECT_LT((result.UV.row(disk.boundary[p]) - circle.row(static_cast<Eigen::Index>(p))).norm(), 1e-15);
  EXPECT_EQ(result.report.pinned, static_cast<int>(disk.boundary.size()));
  EXPECT_EQ(result.report.distortion.flipped, 0);
  EXPECT_LT(result.report.distortion.energy, result.report.solve.initial_energy);
}

TEST(ArapParameterize, AnyScaleGivesTheSameMapInItsUnits) {
  // The solve runs on V / 2^k, exactly: a mesh at 1e150 (areas 1e300) and one at 1e-150 map like the
  // mesh at size 1, to rounding of the same operations.
  const test::TestMesh cap = test::spherical_cap(5, 14, 0.6 * M_PI);
  const ParamResult unit = arap_parameterize(cap.V, cap.F);
  for (double scale : {0x1p+500, 0x1p-500}) {
    const ParamResult scaled = arap_parameterize(cap.V * scale, cap.F);
    EXPECT_LT((scaled.UV / scale - unit.UV).cwiseAbs().maxCoeff(), 1e-12);
    EXPECT_NEAR(scaled.report.distortion.energy / (scale * scale), unit.report.distortion.energy, 1e-12);
  }
}

TEST(ArapParameterize, RefusesBadOptions) {
  const test::TestMesh disk = test::flat_disk(2, 8);
  ParamOptions options;
  options.boundary = ParamBoundary::Circle; // with the LSCM start
  EXPECT_THROW(arap_parameterize(disk.V, disk.F, options), InputError);
  options = {};
  options.solve.max_iterations = -1;
  EXPECT_THROW(arap_parameterize(disk.V, disk.F, options), InputError);
  options = {};
  options.step_fraction = 1;
  EXPECT_THROW(arap_parameterize(disk.V, disk.F, options), InputError);
  options = {};
  options.solve.tolerance = std::nan("");
  EXPECT_THROW(arap_parameterize(disk.V, disk.F, options), InputError);
  options = {};
  options.solve.forces = Eigen::MatrixXd::Ones(disk.V.rows(), 2);
  EXPECT_THROW(arap_parameterize(disk.V, disk.F, options), InputError);
  EXPECT_THROW(parse_param_init("spectral"), InputError);
}

// The three disks with the defaults: no flipped triangle, and an energy at the best uniform scale
// at most 1.02 x the lower of libigl's and CGAL's (issue 31: camelhead 0.8009, lion 0.8656, face 1031).
TEST(ArapParameterize, SharedDisksFlipFreeAtThePeersEnergy) {
  const struct {
    const char* name;
    double peer_energy;
  } cases[] = {{"camelhead.off", 0.8009}, {"lion.off", 0.8656}, {"face.obj", 1031}};
  for (const auto& c : cases) {
    const std::string path = test::shared_mesh_in_loop(c.name);
    if (path.empty()) continue;
    const MeshData mesh = read_mesh(path);
    const ParamReport report = arap_parameterize(mesh.V, mesh.F).report;
    EXPECT_EQ(report.distortion.flipped, 0) << c.name;
    EXPECT_LE(report.distortion.scaled_energy, 1.02 * c.peer_energy) << c.name;
  }
}

} // namespace
} // namespace iarap
