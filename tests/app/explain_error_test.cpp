// The tool's wording of the library's solver errors (issue 20, item 5): each names the cause and the flag
// that fixes it. The library messages below are the ones arap_precompute / SparseCholesky / the tracer
// throw; the conditions behind the last three are hard to build on purpose, so the wording is tested here.
#include "../app/common/explain_error.h" // the tool's sources: tests/ is on the include path, app/ is not

#include <gtest/gtest.h>

namespace {

using iarap::cli::ErrorContext;
using iarap::cli::explain_solver_error;

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

} // namespace

TEST(ExplainError, UnconstrainedComponentNamesTheFlags) {
  const std::string m = explain_solver_error(
      "ARAP: connected component 1 (12 vertices, e.g. vertex 7) has no constrained vertex, so the system is "
      "singular; constrain one of its vertices or enable pin_unconstrained_components",
      {"scan.ply", false});
  EXPECT_TRUE(contains(m, "pass --pin-unconstrained")) << m;
  EXPECT_FALSE(contains(m, "pin_unconstrained_components")) << m;
}

TEST(ExplainError, SingularMatrixGetsCauseAndFix) {
  const std::string m = explain_solver_error(
      "sparse Cholesky: the 605 x 605 matrix is singular (zero pivot in LDL^T)", {"m.obj", false});
  EXPECT_TRUE(contains(m, "cause:")) << m;
  EXPECT_TRUE(contains(m, "`iarap info m.obj`")) << m;
  EXPECT_TRUE(contains(m, "--repair")) << m;
  EXPECT_TRUE(contains(m, "--method iarap")) << m;
}

TEST(ExplainError, NonFiniteEntryPointsToDegenerateFaces) {
  const std::string m = explain_solver_error("sparse Cholesky: entry (1, 1) is not finite", {"m.obj", false});
  EXPECT_TRUE(contains(m, "degenerate face")) << m;
  EXPECT_TRUE(contains(m, "--repair drops zero-area faces")) << m;
}

TEST(ExplainError, TracingFailureGetsCauseAndFix) {
  const std::string m = explain_solver_error(
      "tracing intrinsic edge 22 (8 -> 694) over the input mesh failed: the line ends inside input face 5",
      {"m.obj", false});
  EXPECT_TRUE(contains(m, "nearly degenerate faces")) << m;
  EXPECT_TRUE(contains(m, "--method spokes-rims")) << m;
}

TEST(ExplainError, RepairedRunSaysWhichNumbering) {
  const std::string m = explain_solver_error(
      "ARAP: face 3 is degenerate (zero area): its cotangent weights are not finite", {"m.obj", true});
  EXPECT_TRUE(contains(m, "refer to the repaired mesh, not to m.obj")) << m;
}

// check_mesh names its repair in library terms; the tool names its flag instead, the rest of the message
// as it was.
TEST(ExplainError, MeshWarningsNameTheRepairFlag) {
  using iarap::cli::deform_repair_flag;
  using iarap::cli::name_repair;
  EXPECT_EQ(name_repair("3 vertices are used by no face; first: vertex 7; repair_mesh removes them "
                        "(RepairOptions::remove_unreferenced)",
                        deform_repair_flag),
            "3 vertices are used by no face; first: vertex 7; `iarap deform --repair` removes them");
  EXPECT_EQ(name_repair("the mesh falls apart (STL); repair_mesh welds it (RepairOptions::weld)", "the tool"),
            "the mesh falls apart (STL); the tool welds it");
  const std::string other = "2 edges are non-manifold (3 or more faces); first: edge (0, 1) with 3 faces";
  EXPECT_EQ(name_repair(other, deform_repair_flag), other);
}
