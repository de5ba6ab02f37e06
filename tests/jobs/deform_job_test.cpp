// The deformation job (iarap/jobs/deform_job.h), the pipeline every front-end calls: the same numbers as
// the solver called by hand, at any scale, through the tool too; a repaired mesh keeps its constraints;
// forces need every body held.
#include "iarap/jobs/deform_job.h"

#include "iarap/core/errors.h"
#include "iarap/io/read_mesh.h"
#include "iarap/scene/read_scenario.h"
#include "mesh/small_meshes.h"
#include "test_support.h"

#include <gtest/gtest.h>

#include <cmath>

namespace iarap {
namespace {

struct Bunny {
  MeshData mesh = read_mesh(test::data_path("bunny.off"));
  DeformConstraints constraints{read_scenario(test::data_path("bunny_scenario.json")), {}};
};

ArapSolveOptions plain(int iterations) {
  ArapSolveOptions solve;
  solve.accelerator = ArapAccelerator::None;
  solve.max_iterations = iterations;
  solve.tolerance = -1;
  return solve;
}

TEST(DeformJob, SameNumbersAsTheSolverCalledByHand) {
  const Bunny bunny;
  const DeformScene scene = prepare_deform(bunny.mesh, bunny.constraints);
  ASSERT_TRUE(scene.check.usable());
  const DeformResult result = solve_deform(scene, ArapOptions{}, plain(10));
  // By hand on the file's coordinates: the job's power-of-two scaling is exact, so only the rounding of
  // the same operations on other exponents separates the two (relative 1e-12 of the diagonal is generous).
  ArapData data = arap_precompute(scene.mesh.V, scene.mesh.F, scene.constraints.fixed);
  Eigen::MatrixXd U = scene.mesh.V;
  const ArapReport report = arap_solve(data, scene.constraints.targets, U, plain(10));
  EXPECT_LT((result.U - U).cwiseAbs().maxCoeff(), 1e-12 * scene.check.bbox_diagonal);
  EXPECT_NEAR(result.report.energies.back(), report.energies.back(), 1e-10 * report.energies.back());
  EXPECT_EQ(result.report.iterations, 10);
  EXPECT_FALSE(result.planar);
}

TEST(DeformJob, AnyScaleGivesTheSameDeformationInItsUnits) {
  const Bunny bunny;
  const DeformScene scene = prepare_deform(bunny.mesh, bunny.constraints);
  const DeformResult unit = solve_deform(scene, ArapOptions{}, plain(5));
  for (double scale : {0x1p+300, 0x1p-300}) {
    MeshData mesh = bunny.mesh;
    mesh.V *= scale;
    DeformConstraints constraints;
    constraints.set = scene.constraints;
    constraints.set.targets *= scale;
    const DeformResult result = solve_deform(prepare_deform(mesh, constraints), ArapOptions{}, plain(5));
    EXPECT_LT((result.U / scale - unit.U).cwiseAbs().maxCoeff(), 1e-12) << scale;
    EXPECT_NEAR(result.report.energies.back() / (scale * scale), unit.report.energies.back(),
                1e-12 * unit.report.energies.back());
  }
}

TEST(DeformJob, RepairCarriesTheConstraintsOver) {
  // The bunny with its first vertex duplicated at the end and face 0 pointing at the copy: the repair welds
  // it back, and a constraint given on the copy lands on the vertex.
  Bunny bunny;
  const Eigen::Index n = bunny.mesh.V.rows();
  bunny.mesh.V.conservativeResize(n + 1, 3);
  bunny.mesh.V.row(n) = bunny.mesh.V.row(0);
  for (int c = 0; c < 3; ++c)
    if (bunny.mesh.F(0, c) == 0) bunny.mesh.F(0, c) = static_cast<int>(n);
  DeformConstraints constraints;
  constraints.set.fixed = Eigen::Vector2i(static_cast<int>(n), 100);
  constraints.set.targets = Eigen::MatrixXd(2, 3);
  constraints.set.targets << bunny.mesh.V.row(0) + Eigen::RowVector3d(0, 0.01, 0), bunny.mesh.V.row(100);
  DeformPrepareOptions repair;
  repair.repair = true;
  const DeformScene scene = prepare_deform(bunny.mesh, constraints, repair);
  EXPECT_EQ(scene.mesh.V.rows(), n);
  EXPECT_FALSE(scene.repairs.empty());
  ASSERT_EQ(scene.constraints.fixed.size(), 2);
  EXPECT_EQ(scene.constraints.fixed(0), 0);
  const DeformResult result = solve_deform(scene, ArapOptions{}, plain(3));
  EXPECT_LT((result.U.row(0) - constraints.set.targets.row(0)).norm(), 1e-12);
}

// Soft constraints carried over a repair (issue 47 item 2): two closed cones touching at their tips (the
// repair splits the tip into two copies), one side face given reversed (the repair turns it back, which
// permutes its corners) and one given twice (the duplicate goes).
TEST(DeformJob, RepairCarriesSoftConstraintsAndFacePointsOver) {
  const test::SmallMesh cones = test::two_cones_sharing_a_tip();
  MeshData mesh;
  mesh.V = cones.V;
  mesh.F.resize(13, 3);
  mesh.F << cones.F, cones.F.row(8);
  mesh.F.row(2) = Eigen::RowVector3i(cones.F(2, 0), cones.F(2, 2), cones.F(2, 1)); // reversed
  DeformConstraints constraints;
  ConstraintSet& c = constraints.set;
  c.fixed = Eigen::Vector2i(1, 5); // one base vertex of each cone
  c.targets = Eigen::MatrixXd(2, 3);
  c.targets << mesh.V.row(1), mesh.V.row(5);
  SoftConstraintSet& soft = c.soft;
  soft.vertices = Eigen::VectorXi::Constant(1, 0); // the tip: split in two
  soft.vertex_weights = Eigen::VectorXd::Constant(1, 4.0);
  soft.vertex_targets = Eigen::RowVector3d(0.1, 0.2, 0.05);
  // The reversed face, the duplicate, a face on the tip's copy.
  soft.faces = (Eigen::VectorXi(3) << 2, 12, 7).finished();
  soft.barycentric = Eigen::MatrixXd(3, 3);
  soft.barycentric << 0.2, 0.3, 0.5, 0.6, 0.3, 0.1, 0.1, 0.1, 0.8;
  soft.face_weights = Eigen::Vector3d(1, 2, 3);
  soft.face_targets = Eigen::MatrixXd::Zero(3, 3);
  soft.origins = {"c.txt:3", "c.txt:4", "c.txt:5", "c.txt:6"};
  DeformPrepareOptions repair;
  repair.repair = true;
  const DeformScene scene = prepare_deform(mesh, constraints, repair);
  ASSERT_EQ(scene.mesh.V.rows(), 10);
  const SoftConstraintSet& out = scene.constraints.soft;
  // W = 4 shared by the tip's two copies, each at the tip.
  ASSERT_EQ(out.vertices.size(), 2);
  for (Eigen::Index k = 0; k < 2; ++k) {
    EXPECT_EQ(scene.mesh.V.row(out.vertices(k)), mesh.V.row(0));
    EXPECT_EQ(out.vertex_weights(k), 2.0);
    EXPECT_EQ(out.vertex_targets.row(k), soft.vertex_targets.row(0));
  }
  // Each face point is the same point of space on the face that stands for its face.
  ASSERT_EQ(out.faces.size(), 3);
  for (Eigen::Index k = 0; k < 3; ++k) {
    Eigen::RowVector3d before = Eigen::RowVector3d::Zero(), after = Eigen::RowVector3d::Zero();
    for (int j = 0; j < 3; ++j) {
      before += soft.barycentric(k, j) * mesh.V.row(mesh.F(soft.faces(k), j));
      after += out.barycentric(k, j) * scene.mesh.V.row(scene.mesh.F(out.faces(k), j));
    }
    EXPECT_LT((after - before).norm(), 1e-15) << k;
    EXPECT_EQ(out.face_weights(k), soft.face_weights(k));
  }
  // Each copy of the tip names the line it came from.
  EXPECT_EQ(out.origins, (std::vector<std::string>{"c.txt:3", "c.txt:3", "c.txt:4", "c.txt:5", "c.txt:6"}));
  const DeformResult result = solve_deform(scene, ArapOptions{}, plain(20));
  EXPECT_TRUE(result.U.allFinite());

  // A point on a face the repair removes (degenerate: two corners the same) is named.
  MeshData collapsed = mesh;
  collapsed.F.conservativeResize(14, 3);
  collapsed.F.row(13) = Eigen::RowVector3i(1, 1, 2);
  soft.faces(1) = 13;
  try {
    prepare_deform(collapsed, constraints, repair);
    FAIL() << "a point on a removed face was carried over";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("c.txt:5"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("face 13 was removed"), std::string::npos) << e.what();
  }
}

TEST(DeformJob, ForcesNeedEveryBodyHeld) {
  // Two bunnies, the second one free: under gravity it has no equilibrium, and the job says which.
  const Bunny bunny;
  MeshData two = bunny.mesh;
  const Eigen::Index n = two.V.rows();
  two.V.conservativeResize(2 * n, 3);
  two.V.bottomRows(n) = bunny.mesh.V.rowwise() + Eigen::RowVector3d(10, 0, 0);
  two.F.conservativeResize(2 * bunny.mesh.F.rows(), 3);
  two.F.bottomRows(bunny.mesh.F.rows()) = bunny.mesh.F.array() + static_cast<int>(n);
  StaticForces gravity;
  gravity.present = true;
  gravity.gravity = Eigen::Vector3d(0, -1, 0);
  DeformConstraints first_only; // the scenario's vertices, all on the first bunny
  first_only.set = prepare_deform(bunny.mesh, bunny.constraints).constraints;
  const DeformScene scene = prepare_deform(two, first_only);
  try {
    solve_deform(scene, ArapOptions{}, plain(1), gravity);
    FAIL() << "a free body under gravity was solved";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("connected component 1"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("no static equilibrium"), std::string::npos) << e.what();
  }
}

} // namespace
} // namespace iarap
