// What `iarap deform --repair` does to a mesh file, as the robustness suite and the pipeline fuzz run it:
// read, repair (deform's options), check, then precompute and solve with each of the three methods on a
// small edit. Every stage either succeeds or throws an iarap::Error naming what is wrong.
#pragma once
#include "iarap/core/errors.h"
#include "iarap/io/read_mesh.h"
#include "iarap/mesh/normalize_scale.h"
#include "iarap/mesh/repair.h"
#include "iarap/mesh/validate.h"
#include "iarap/solver/arap.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

namespace iarap::test {

// The repair `deform --repair` applies.
inline RepairOptions deform_repair_options() {
  RepairOptions options;
  options.remove_zero_area = true;
  return options;
}

// The repaired mesh of the file at `path`; throws the reader's InputError, or TopologyError naming the file
// and check_mesh's first error when ARAP cannot deform the repaired mesh (one that is only not an oriented
// manifold, a non-orientable piece, deforms on the tufted cover).
inline RepairResult read_and_repair(const std::string& path) {
  const MeshData mesh = read_mesh(path);
  RepairResult repaired = repair_mesh(mesh.V, mesh.F, deform_repair_options());
  const MeshReport check = check_mesh(repaired.V, repaired.F);
  if (!check.deformable())
    throw TopologyError(path + ": mesh not usable after repair: " + check.errors.front());
  return repaired;
}

// The invariants of a repaired mesh whatever the input: no non-manifold edge, no vertex where a closed fan
// touches another, consistent orientation unless a piece is non-orientable. Records a failure naming
// `what` otherwise.
inline void expect_repaired_topology(const RepairResult& r, const std::string& what) {
  const MeshReport check = check_mesh(r.V, r.F);
  EXPECT_EQ(check.non_manifold_edges, 0) << what;
  for (const std::string& error : check.errors)
    EXPECT_EQ(error.find("non-manifold (a closed fan"), std::string::npos) << what << ": " << error;
  if (check.non_orientable_components == 0) {
    EXPECT_EQ(check.inconsistently_oriented_edges, 0) << what;
  }
  EXPECT_EQ(r.counts.non_orientable_pieces, check.non_orientable_components) << what;
}

// One solve with `method` on V / s (the CLI's exact power-of-two scaling): vertex 0 stays, the vertex of
// largest x moves by a tenth of the diagonal along y; components without a constraint are pinned (the
// repair may split a mesh into pieces). Checks what holds for any mesh: a finite result with the
// constrained vertices at their targets. Throws what the solver throws.
inline void deform_with(ArapMethod method, const Eigen::MatrixXd& V_in, const Eigen::MatrixXi& F,
                        int iterations) {
  const Eigen::MatrixXd V = V_in / normalizing_scale(V_in);
  Eigen::Index handle = 0;
  V.col(0).maxCoeff(&handle);
  const Eigen::VectorXi fixed =
      handle == 0 ? Eigen::VectorXi::Zero(1) : (Eigen::VectorXi(2) << 0, static_cast<int>(handle)).finished();
  Eigen::MatrixXd targets(fixed.size(), 3);
  for (Eigen::Index k = 0; k < fixed.size(); ++k) targets.row(k) = V.row(fixed(k));
  targets(fixed.size() - 1, 1) += 0.1 * bounding_box_diagonal(V);
  ArapOptions options;
  options.method = method;
  options.pin_unconstrained_components = true;
  ArapData data = arap_precompute(V, F, fixed, options);
  Eigen::MatrixXd U = V;
  ArapSolveOptions solve;
  solve.max_iterations = iterations;
  const ArapReport report = arap_solve(data, targets, U, solve);
  EXPECT_TRUE(U.allFinite()) << arap_method_name(method);
  EXPECT_TRUE(std::isfinite(report.energies.empty() ? report.initial_energy : report.energies.back()));
  for (Eigen::Index k = 0; k < fixed.size(); ++k)
    EXPECT_EQ(U.row(fixed(k)), targets.row(k)) << arap_method_name(method) << ": vertex " << fixed(k);
}

inline constexpr ArapMethod every_method[] = {ArapMethod::Arap, ArapMethod::SpokesRims, ArapMethod::Iarap};

inline void deform_with_every_method(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, int iterations) {
  for (const ArapMethod method : every_method) deform_with(method, V, F, iterations);
}

} // namespace iarap::test
