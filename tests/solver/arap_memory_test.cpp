// The memory a precomputation holds, part by part (issue 44): every part counted, rotations exactly, and
// linear in the mesh size.
#include "iarap/core/errors.h"
#include "iarap/mesh/subdivide.h"
#include "iarap/solver/arap.h"
#include "iarap/solver/arap_memory.h"
#include "solver_fixtures.h"

#include "solver/streamed_layout.h" // the layout the iterations stream

#include <gtest/gtest.h>

namespace {

using namespace iarap;

ArapData bunny_data(ArapMethod method, int subdivisions, bool keep_elements = false) {
  test::SolverMesh m = test::bunny();
  subdivide_midpoint(m.V, m.F, subdivisions);
  ArapOptions options;
  options.method = method;
  options.pin_unconstrained_components = true;
  options.keep_elements = keep_elements;
  return arap_precompute(m.V, m.F, test::to_vector(test::axis_band(m.V, 1, 0.1, -1)), options);
}

// A 31 x 31 curved patch with jittered, non-Delaunay triangles: small enough for the sanitizer run (the
// bunny's six precomputes and smoothed solves took 76 s there).
ArapData patch_data(ArapMethod method, bool keep_elements) {
  const test::SolverMesh m = test::bumpy_patch(30);
  ArapOptions options;
  options.method = method;
  options.keep_elements = keep_elements;
  return arap_precompute(m.V, m.F, test::to_vector(test::axis_band(m.V, 1, 0.1, -1)), options);
}

TEST(ArapMemory, EveryPartIsCountedAndRotationsExactly) {
  for (const ArapMethod method : {ArapMethod::Arap, ArapMethod::SpokesRims, ArapMethod::Iarap}) {
    const ArapData data = bunny_data(method, 0, true);
    const ArapMemory m = arap_memory(data);
    EXPECT_GT(m.mesh, static_cast<std::size_t>(data.V.size()) * sizeof(double));
    // Each element holds at least its b (3 ints, 3 doubles), s_hat (3 doubles) and w.
    EXPECT_GT(m.elements,
              static_cast<std::size_t>(data.elements.size()) * (3 * sizeof(int) + 7 * sizeof(double)));
    EXPECT_GT(m.system, static_cast<std::size_t>(data.L.nonZeros()) * sizeof(double));
    // The factor holds at least L_ff's lower triangle (its fill only adds to it).
    EXPECT_GT(m.factor, static_cast<std::size_t>(data.L.nonZeros() / 2) * sizeof(double));
    EXPECT_GT(m.kept_matrix, 0u);
    EXPECT_EQ(m.rotations, data.R.capacity() * sizeof(Eigen::Matrix3d));
    // Each cell entry holds at least its b (3 ints, 3 doubles) and w, beside the rest positions.
    EXPECT_GT(m.streamed,
              detail::streamed(data.elements).cell_entry.size() * (3 * sizeof(int) + 4 * sizeof(double)) +
                  static_cast<std::size_t>(data.V.size()) * sizeof(double));
    EXPECT_EQ(detail::streamed(data.elements).cell_entry.size(), data.elements.cell_element.size());
    std::size_t sum = 0;
    visit_arap_memory(m, [&](const char* name, std::size_t bytes) {
      if (std::string(name) != "total") sum += bytes;
    });
    EXPECT_EQ(sum, m.total()) << arap_method_name(method);
  }
}

// By default the precompute releases the element arrays (ArapOptions::keep_elements): they count 0, the
// rest is as with them kept, and the solve reads the same streamed layout, so its results are the same bits.
TEST(ArapMemory, ReleasedElementsCountNothingAndSolveTheSame) {
  for (const ArapMethod method : {ArapMethod::Arap, ArapMethod::SpokesRims, ArapMethod::Iarap}) {
    const std::string what = arap_method_name(method);
    ArapData kept = patch_data(method, true), released = patch_data(method, false);
    const ArapMemory m_kept = arap_memory(kept), m_released = arap_memory(released);
    EXPECT_FALSE(kept.elements.arrays_released) << what;
    EXPECT_TRUE(released.elements.arrays_released) << what;
    // What is left of the elements is the cell graph: about 6 neighbours a cell, 4 bytes each.
    EXPECT_LT(m_released.elements, m_kept.elements / 5) << what;
    EXPECT_LT(m_released.elements, static_cast<std::size_t>(released.elements.num_cells) * 12 * sizeof(int))
        << what;
    EXPECT_EQ(m_released.streamed, m_kept.streamed) << what;
    EXPECT_EQ(m_released.total() - m_released.elements, m_kept.total() - m_kept.elements) << what;
    EXPECT_EQ(released.min_weight, kept.min_weight) << what;
    EXPECT_EQ(released.negative_weights, (kept.elements.w.array() < 0.0).count()) << what;
    EXPECT_EQ(released.elements.num_cells, kept.elements.num_cells) << what;
    // The same L (the iARAP one is twice the cotan Laplacian either way).
    EXPECT_EQ((released.L - kept.L).norm(), 0.0) << what;
    const Eigen::VectorXi& fixed = kept.fixed;
    Eigen::MatrixXd targets(fixed.size(), 3);
    for (Eigen::Index k = 0; k < fixed.size(); ++k)
      targets.row(k) = kept.V.row(fixed(k)) + Eigen::RowVector3d(0.0, 0.02, 0.01);
    ArapSolveOptions solve;
    solve.max_iterations = 5;
    solve.accelerator = ArapAccelerator::None; // the plain step: every path reads the same layout
    Eigen::MatrixXd U_kept = kept.V, U_released = released.V;
    const ArapReport a = arap_solve(kept, targets, U_kept, solve);
    const ArapReport b = arap_solve(released, targets, U_released, solve);
    // The first solve keeps L's free rows (a value and a column a nonzero, at least the diagonal's).
    EXPECT_GE(arap_memory(kept).system,
              m_kept.system + static_cast<std::size_t>(kept.free.size()) * (sizeof(double) + sizeof(int)))
        << what;
    EXPECT_EQ((U_kept - U_released).cwiseAbs().maxCoeff(), 0.0) << what;
    EXPECT_EQ(a.energies, b.energies) << what;
    EXPECT_EQ(arap_energy(kept, U_kept), arap_energy(released, U_released)) << what;
    EXPECT_EQ((arap_gradient(kept, U_kept) - arap_gradient(released, U_released)).cwiseAbs().maxCoeff(), 0.0)
        << what;
    // Rotation smoothing reads the cell graph release_element_arrays kept: the same smoothing.
    ArapSolveOptions smooth = solve;
    smooth.rotation_smoothing = 0.1;
    Eigen::MatrixXd S_kept = kept.V, S_released = released.V;
    arap_solve(kept, targets, S_kept, smooth);
    arap_solve(released, targets, S_released, smooth);
    EXPECT_EQ((S_kept - S_released).cwiseAbs().maxCoeff(), 0.0) << what;
    EXPECT_GT((S_kept - U_kept).cwiseAbs().maxCoeff(), 0.0) << what;
    // Refactorizing for a new constrained set needs L only.
    arap_set_fixed(released, fixed.head(fixed.size() - 1));
    EXPECT_EQ(released.fixed.size(), fixed.size() - 1) << what;
    EXPECT_THROW(element_system_matrix(released.elements), InputError) << what;
  }
}

// With rigid groups the elements stay (the groups' covariances read them in the file's order).
// While the iterations run, the caller's U is released (its rows live in the iterations' order): an
// on_iteration callback sees it empty; afterwards it has its shape back with the constrained rows at their
// targets (fixed) and the free ones moved, the same bits as a solve from a copy of the same guess. The hard
// points' setup reads U before the release.
TEST(ArapMemory, TheCallersPositionsAreReleasedWhileTheSolveRuns) {
  const ArapData reference = patch_data(ArapMethod::Iarap, false);
  const Eigen::MatrixXd V = reference.V;
  Eigen::MatrixXd targets(reference.fixed.size(), 3);
  for (Eigen::Index k = 0; k < targets.rows(); ++k)
    targets.row(k) = V.row(reference.fixed(k)) + Eigen::RowVector3d(0.0, 0.2, 0.1);
  for (const ArapAccelerator accelerator : {ArapAccelerator::None, ArapAccelerator::Newton}) {
    ArapData data = reference;
    ArapSolveOptions options;
    options.accelerator = accelerator;
    options.max_iterations = 4;
    std::vector<Eigen::Index> sizes;
    Eigen::MatrixXd U = V;
    options.on_iteration = [&](const ArapReport&) {
      sizes.push_back(U.size());
      return true;
    };
    arap_solve(data, targets, U, options);
    ASSERT_FALSE(sizes.empty());
    for (const Eigen::Index size : sizes) EXPECT_EQ(size, 0);
    ASSERT_EQ(U.rows(), V.rows());
    ASSERT_EQ(U.cols(), 3);
    for (Eigen::Index k = 0; k < targets.rows(); ++k) EXPECT_EQ(U.row(reference.fixed(k)), targets.row(k));
    EXPECT_GT((U - V).norm(), 0.0);
    ArapData again = reference;
    Eigen::MatrixXd U2 = V;
    options.on_iteration = nullptr;
    arap_solve(again, targets, U2, options);
    EXPECT_EQ(U, U2);
  }
}

TEST(ArapMemory, RigidGroupsKeepTheElements) {
  test::SolverMesh m = test::bunny();
  ArapOptions options;
  options.pin_unconstrained_components = true;
  options.rigid_groups = {{3, 4, 5}};
  const ArapData data = arap_precompute(m.V, m.F, test::to_vector(test::axis_band(m.V, 1, 0.1, -1)), options);
  EXPECT_FALSE(data.elements.arrays_released);
  EXPECT_GT(arap_memory(data).elements, 0u);
}

// One 1-to-4 subdivision multiplies the vertices by about 4: what is held grows by about as much (the
// factor's fill grows a little faster than linearly on a surface, n log n for nested dissection).
TEST(ArapMemory, GrowsLinearlyWithTheMesh) {
  const ArapData coarse = bunny_data(ArapMethod::Iarap, 0), fine = bunny_data(ArapMethod::Iarap, 1);
  const double vertices = static_cast<double>(fine.V.rows()) / static_cast<double>(coarse.V.rows());
  const double held = static_cast<double>(arap_memory(fine).total()) / arap_memory(coarse).total();
  EXPECT_GT(held, 0.8 * vertices);
  EXPECT_LT(held, 1.5 * vertices);
}

} // namespace
