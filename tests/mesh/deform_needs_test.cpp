// One verdict (issue 47, item 3): for every usable mesh, deform_needs (what `info` prints) names exactly the
// methods whose precompute refuses the mesh, and the repair it asks for makes them accept it.
#include "iarap/io/read_mesh.h"
#include "iarap/mesh/repair.h"
#include "iarap/mesh/validate.h"
#include "iarap/solver/arap.h"
#include "small_meshes.h"
#include "test_support.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <utility>
#include <vector>

namespace {

using namespace iarap;

// Whether `method`'s precompute accepts the mesh (every component pinned: the components' need is given).
bool accepted(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, const std::string& method) {
  ArapOptions options;
  options.method = parse_arap_method(method);
  options.pin_unconstrained_components = true;
  try {
    arap_precompute(V, F, Eigen::VectorXi::Constant(1, F(0, 0)), options);
    return true;
  } catch (const Error&) {
    return false;
  }
}

bool needs_repair(const std::vector<DeformNeed>& needs, const std::string& method) {
  for (const DeformNeed& need : needs)
    if (need.flag == "--repair")
      for (const std::string& m : need.methods)
        if (m == method) return true;
  return false;
}

void expect_one_verdict(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, const std::string& name) {
  const MeshReport report = check_mesh(V, F);
  if (!report.deformable()) return; // info says "not usable": nothing to agree on
  const std::vector<DeformNeed> needs = deform_needs(report);
  RepairOptions options;
  options.remove_zero_area = true;
  const RepairResult repaired = repair_mesh(V, F, options);
  for (const std::string method : {"arap", "spokes-rims", "iarap"}) {
    EXPECT_EQ(accepted(V, F, method), !needs_repair(needs, method)) << name << ", " << method;
    if (needs_repair(needs, method)) {
      EXPECT_TRUE(accepted(repaired.V, repaired.F, method)) << name << " after --repair, " << method;
    }
  }
}

// A square pyramid over a unit base whose first face is a needle `height` high on the base's edge.
test::SmallMesh needle(double height) {
  test::SmallMesh m;
  m.V.resize(6, 3);
  m.V << 0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 0.5, -height, 0, 0.5, 0.5, 0.3;
  m.F.resize(5, 3);
  m.F << 0, 4, 1, 0, 1, 5, 1, 2, 5, 2, 3, 5, 3, 0, 5;
  return m;
}

// Input that is only not an oriented manifold (issue 47, item 1) needs no repair for any method: iARAP runs
// on its tufted cover, original ARAP and spokes-and-rims on its own edges and faces.
TEST(DeformNeeds, NotAnOrientedManifoldNeedsNoRepair) {
  const std::vector<std::pair<std::string, test::SmallMesh>> meshes{
      {"fin", test::fin(4)},
      {"cubes at a corner", test::two_cubes_at_a_corner()},
      {"mixed orientation", test::with_mixed_orientation(test::subdivided_octahedron(), 3)},
      {"klein bottle", test::klein_bottle(12, 8)},
      {"moebius strip", test::moebius_strip()}};
  for (const auto& [name, m] : meshes) {
    const MeshReport report = check_mesh(m.V, m.F);
    EXPECT_FALSE(report.usable()) << name;
    EXPECT_EQ(report.oriented_manifold_errors, static_cast<int>(report.errors.size())) << name;
    EXPECT_TRUE(report.deformable()) << name;
    for (const std::string method : {"arap", "spokes-rims", "iarap"})
      EXPECT_FALSE(needs_repair(deform_needs(report), method)) << name << ", " << method;
    expect_one_verdict(m.V, m.F, name);
  }
  // With an error no method handles (a NaN), the mesh is not deformable.
  test::SmallMesh broken = test::fin(3);
  broken.V(4, 0) = NAN;
  EXPECT_FALSE(check_mesh(broken.V, broken.F).deformable());
}

// Needles from harmless to degenerate: 1e-10 was the case `info` called usable and original ARAP refused
// (its short sides round to exactly half the base); 1e-13 the one `info` sent to --repair although iARAP
// runs on it.
TEST(DeformNeeds, NeedlesAndZeroAreaFacesGetOneVerdict) {
  for (const double height : {1e-3, 1e-7, 1e-9, 1e-10, 1e-13, 1e-16, 0.0}) {
    const test::SmallMesh m = needle(height);
    expect_one_verdict(m.V, m.F, "needle " + std::to_string(height));
  }
  const test::SmallMesh needle_10 = needle(1e-10);
  EXPECT_EQ(check_mesh(needle_10.V, needle_10.F).zero_area_faces, 1);
}

// Coincident vertices (a seam) and several components: warnings and the pinning need, no repair need.
TEST(DeformNeeds, SeamsAreAWarningNotANeed) {
  test::SmallMesh m = test::octahedron();
  const Eigen::Index n = m.V.rows();
  m.V.conservativeResize(n + 1, 3);
  m.V.row(n) = m.V.row(0);
  m.F(0, 0) = static_cast<int>(n); // face 0 uses the copy: a seam at vertex 0
  const MeshReport report = check_mesh(m.V, m.F);
  ASSERT_TRUE(report.usable());
  EXPECT_GT(report.coincident_vertices, 0);
  for (const DeformNeed& need : deform_needs(report)) EXPECT_NE(need.flag, "--repair");
  expect_one_verdict(m.V, m.F, "seam");
  const test::SmallMesh two = test::two_cones_sharing_a_tip();
  const RepairResult split = repair_mesh(two.V, two.F);
  const std::vector<DeformNeed> needs = deform_needs(check_mesh(split.V, split.F));
  ASSERT_EQ(needs.size(), 1u);
  EXPECT_EQ(needs[0].flag, "--pin-unconstrained");
}

// The shared meshes under 30K vertices (the larger ones take the same code paths).
TEST(DeformNeeds, SharedMeshesGetOneVerdict) {
  for (const char* name : {"bunny.off", "beetle.off", "lion.off", "camelhead.off", "face.obj", "ogre.obj",
                           "cube_40k.obj", "3holes.off", "cheburashka.off", "spike.ply", "planexy.off"}) {
    const std::string path = test::shared_mesh_in_loop(name);
    if (path.empty()) continue;
    const MeshData mesh = read_mesh(path);
    expect_one_verdict(mesh.V, mesh.F, name);
  }
}

} // namespace
