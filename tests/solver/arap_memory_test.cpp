// The memory a precomputation holds, part by part (issue 44): every part counted, rotations exactly, and
// linear in the mesh size.
#include "iarap/mesh/subdivide.h"
#include "iarap/solver/arap.h"
#include "iarap/solver/arap_memory.h"
#include "solver_fixtures.h"

#include <gtest/gtest.h>

namespace {

using namespace iarap;

ArapData bunny_data(ArapMethod method, int subdivisions) {
  test::SolverMesh m = test::bunny();
  subdivide_midpoint(m.V, m.F, subdivisions);
  ArapOptions options;
  options.method = method;
  options.pin_unconstrained_components = true;
  return arap_precompute(m.V, m.F, test::to_vector(test::axis_band(m.V, 1, 0.1, -1)), options);
}

TEST(ArapMemory, EveryPartIsCountedAndRotationsExactly) {
  for (const ArapMethod method : {ArapMethod::Arap, ArapMethod::SpokesRims, ArapMethod::Iarap}) {
    const ArapData data = bunny_data(method, 0);
    const ArapMemory m = arap_memory(data);
    EXPECT_GT(m.mesh, static_cast<std::size_t>(data.V.size()) * sizeof(double));
    EXPECT_GT(m.elements, 0u);
    EXPECT_GT(m.system, static_cast<std::size_t>(data.L.nonZeros()) * sizeof(double));
    // The factor holds at least L_ff's lower triangle (its fill only adds to it).
    EXPECT_GT(m.factor, static_cast<std::size_t>(data.L.nonZeros() / 2) * sizeof(double));
    EXPECT_GT(m.kept_matrix, 0u);
    EXPECT_EQ(m.rotations, data.R.capacity() * sizeof(Eigen::Matrix3d));
    // Each cell entry holds at least its b (3 ints, 3 doubles), s_hat (3 doubles) and w.
    EXPECT_GT(m.streamed, data.elements.cell_element.size() * (3 * sizeof(int) + 7 * sizeof(double)));
    std::size_t sum = 0;
    visit_arap_memory(m, [&](const char* name, std::size_t bytes) {
      if (std::string(name) != "total") sum += bytes;
    });
    EXPECT_EQ(sum, m.total()) << arap_method_name(method);
  }
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
