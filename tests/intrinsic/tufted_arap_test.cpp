// ARAP on input that is not an oriented manifold: iARAP on the tufted cover, original ARAP and
// spokes-and-rims on the input's own edges and faces (docs/nonmanifold.md).
#include "iarap/mesh/cotan.h"
#include "iarap/mesh/edge_topology.h"
#include "iarap/mesh/validate.h"
#include "iarap/solver/arap.h"
#include "mesh/small_meshes.h"

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <random>
#include <string>
#include <vector>

using namespace iarap;
using iarap::test::SmallMesh;

namespace {

// The octahedron subdivided twice, on the unit sphere, its vertices moved along the sphere at random by up
// to a third of an edge: closed, oriented, with non-Delaunay edges (the flips have work to do) and no four
// cocircular vertices (the Delaunay triangulation is unique, whatever the order of the flips).
SmallMesh jittered_sphere() {
  SmallMesh m = iarap::test::octahedron();
  subdivide_midpoint(m.V, m.F, 2);
  std::mt19937 random(5);
  std::uniform_real_distribution<double> jitter(-0.12, 0.12);
  for (Eigen::Index v = 0; v < m.V.rows(); ++v) {
    m.V.row(v).normalize();
    m.V.row(v) += Eigen::RowVector3d(jitter(random), jitter(random), jitter(random));
    m.V.row(v).normalize();
  }
  return m;
}

// Constraints of the solves below: the vertices of smallest and largest x among those of the faces.
Eigen::VectorXi handles(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F) {
  int low = F(0, 0), high = F(0, 0);
  for (Eigen::Index i = 0; i < F.size(); ++i) {
    const int v = F.data()[i];
    if (V(v, 0) < V(low, 0)) low = v;
    if (V(v, 0) > V(high, 0)) high = v;
  }
  return (Eigen::VectorXi(2) << low, high).finished();
}

Eigen::MatrixXd rows_of(const Eigen::MatrixXd& V, const Eigen::VectorXi& index) {
  Eigen::MatrixXd out(index.size(), 3);
  for (Eigen::Index k = 0; k < index.size(); ++k) out.row(k) = V.row(index(k));
  return out;
}

struct DirtyMesh {
  std::string name;
  SmallMesh mesh;
};

// Each defect of issue 47 on its own: a vertex where two closed fans meet, edges of 3-5 faces, mixed
// orientation, isolated vertices (beside a fin, so that the input takes the cover), a Klein bottle and a
// Moebius strip.
std::vector<DirtyMesh> dirty_meshes() {
  std::vector<DirtyMesh> all;
  all.push_back({"two_cubes_at_a_corner", iarap::test::two_cubes_at_a_corner()});
  for (int k = 3; k <= 5; ++k) all.push_back({"fin_" + std::to_string(k), iarap::test::fin(k)});
  all.push_back({"mixed_orientation", iarap::test::with_mixed_orientation(jittered_sphere(), 5)});
  all.push_back(
      {"isolated_vertices", iarap::test::appended(iarap::test::fin(3), Eigen::MatrixXd::Identity(2, 3) * -3.0,
                                                  Eigen::MatrixXi(0, 3))});
  all.push_back({"klein_bottle", iarap::test::klein_bottle()});
  all.push_back({"moebius_strip", iarap::test::moebius_strip()});
  return all;
}

} // namespace

// On a closed oriented manifold the cover is two copies of the mesh and its weights are halved: the
// elements give the system matrix, the energy and the solve of the normal path. Only the order of the
// additions differs (both copies' elements add into one cell): a few ulps, so 1e-12 relative for L and the
// energy, and 1e-10 of the diagonal for positions after the solve.
TEST(TuftedArap, CoverReproducesTheNormalPathOnAClosedManifold) {
  const SmallMesh m = jittered_sphere();
  const Eigen::VectorXi fixed = handles(m.V, m.F);
  Eigen::MatrixXd targets = rows_of(m.V, fixed);
  targets(1, 1) += 0.3;
  ArapOptions plain, covered;
  plain.keep_elements = covered.keep_elements = true; // the element counts are compared
  covered.intrinsic.tufted_cover = true;
  ArapData normal = arap_precompute(m.V, m.F, fixed, plain);
  ArapData cover = arap_precompute(m.V, m.F, fixed, covered);
  EXPECT_FALSE(normal.intrinsic.tufted_cover);
  EXPECT_TRUE(cover.intrinsic.tufted_cover);
  EXPECT_EQ(cover.intrinsic.cover_vertices, 2 * m.V.rows());
  EXPECT_GT(normal.intrinsic.flips, 0);
  EXPECT_LE((Eigen::MatrixXd(cover.L) - Eigen::MatrixXd(normal.L)).norm(),
            1e-12 * Eigen::MatrixXd(normal.L).norm());
  // Each element appears once per copy with half its weight, and the two halves are merged where they are
  // exactly equal (every unflipped edge: b = e_j - e_i); segments of flipped edges may differ in roundoff
  // between the copies and stay halves.
  EXPECT_GE(cover.min_weight, 0.5 * normal.min_weight - 1e-12);
  EXPECT_LE(cover.min_weight, normal.min_weight + 1e-12);
  EXPECT_GE(cover.elements.size(), normal.elements.size());
  EXPECT_LT(cover.elements.size(), 2 * normal.elements.size());
  std::cout << "elements: " << normal.elements.size() << " (normal path), " << cover.elements.size()
            << " (cover, merged)\n";
  std::mt19937 random(3);
  std::uniform_real_distribution<double> move(-0.1, 0.1);
  Eigen::MatrixXd U = m.V;
  for (Eigen::Index i = 0; i < U.size(); ++i) U.data()[i] += move(random);
  const double energy = arap_energy(normal, U);
  EXPECT_NEAR(arap_energy(cover, U), energy, 1e-12 * energy);
  ArapSolveOptions solve;
  solve.max_iterations = 20;
  Eigen::MatrixXd U_normal = m.V, U_cover = m.V;
  arap_solve(normal, targets, U_normal, solve);
  arap_solve(cover, targets, U_cover, solve);
  EXPECT_LE((U_cover - U_normal).cwiseAbs().maxCoeff(), 1e-10 * bounding_box_diagonal(m.V));
}

// Every dirty mesh deforms with all three methods, with the input's vertices: at rest under rest targets
// (1e-9 of the diagonal: the solve's residual at rest is roundoff), finite and moved under a real edit;
// iARAP's weights are cotangents of an intrinsic Delaunay triangulation (>= -1e-12, the flip tolerance).
TEST(TuftedArap, DirtyMeshesDeformWithEveryMethod) {
  for (const DirtyMesh& dirty : dirty_meshes()) {
    const SmallMesh& m = dirty.mesh;
    const MeshReport check = check_mesh(m.V, m.F);
    EXPECT_FALSE(check.usable()) << dirty.name;
    EXPECT_TRUE(check.deformable()) << dirty.name;
    const double diagonal = bounding_box_diagonal(m.V);
    const Eigen::VectorXi fixed = handles(m.V, m.F);
    for (const ArapMethod method : {ArapMethod::Arap, ArapMethod::SpokesRims, ArapMethod::Iarap}) {
      const std::string what = dirty.name + " " + arap_method_name(method);
      ArapOptions options;
      options.method = method;
      options.pin_unconstrained_components = true;
      options.keep_elements = true;
      ArapData data = arap_precompute(m.V, m.F, fixed, options);
      EXPECT_EQ(data.min_weight, data.elements.w.minCoeff()) << what;
      EXPECT_EQ(data.negative_weights, (data.elements.w.array() < 0.0).count()) << what;
      if (method == ArapMethod::Iarap) {
        EXPECT_TRUE(data.intrinsic.tufted_cover) << what;
        EXPECT_GE(data.min_weight, -1e-12) << what;
      }
      Eigen::MatrixXd U = m.V;
      ArapSolveOptions solve;
      solve.max_iterations = 50;
      arap_solve(data, rows_of(m.V, fixed), U, solve);
      ASSERT_EQ(U.rows(), m.V.rows()) << what;
      EXPECT_LE((U - m.V).cwiseAbs().maxCoeff(), 1e-9 * diagonal) << what << ": not at rest";
      Eigen::MatrixXd targets = rows_of(m.V, fixed);
      targets(1, 1) += 0.1 * diagonal;
      U = m.V;
      arap_solve(data, targets, U, solve);
      EXPECT_TRUE(U.allFinite()) << what;
      EXPECT_EQ(U.row(fixed(1)), targets.row(1)) << what;
      // Isolated vertices have no energy: they stay where they are.
      for (Eigen::Index v = 0; v < m.V.rows(); ++v)
        if ((m.F.array() == v).count() == 0) {
          EXPECT_EQ(U.row(v), m.V.row(v)) << what << ": vertex " << v;
        }
    }
  }
}

// Original ARAP on an edge of k faces: w = sum over the faces of cot(opposite angle) / 2 (Eq. 1 read as a
// sum over the edge's faces), the cotangents as face_cotangents gives them.
TEST(TuftedArap, OriginalArapSumsEveryFaceOfAFin) {
  for (int k = 3; k <= 5; ++k) {
    const SmallMesh m = iarap::test::fin(k);
    const Eigen::MatrixXd C = face_cotangents(m.V, m.F);
    double expected = 0.0;
    for (int f = 0; f < k; ++f) expected += 0.5 * C(f, 2); // corner 2 is the apex, opposite edge (0, 1)
    const ArapElements el = arap_edge_elements(m.V, m.F);
    const EdgeTopology topology = edge_topology(m.F, static_cast<int>(m.V.rows()));
    for (Eigen::Index e = 0; e < topology.E.rows(); ++e)
      if (topology.E(e, 0) == 0 && topology.E(e, 1) == 1) {
        EXPECT_NEAR(el.w(e), expected, 1e-15 * k);
      }
  }
}
