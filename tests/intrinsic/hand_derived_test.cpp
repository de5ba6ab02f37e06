// Tiny meshes whose intrinsic triangulation, segment weights and iARAP system matrix are derived by hand
// (in the comments), so that a wrong split point, an inverted segment weight or a shifted Delaunay
// threshold fails here and not only in a Laplacian identity. Issue 20 planted such bugs: each of these
// tests fails on one of them.
#include "iarap/intrinsic/intrinsic_delaunay.h"
#include "iarap/solver/arap.h"

#include <Eigen/SparseCore>
#include <gtest/gtest.h>

using namespace iarap;

namespace {

// Round-off on coordinates of size 1 after a handful of operations; far below every effect tested (0.1 and
// more for positions and weights).
constexpr double kTight = 1e-12;

// The flat kite A = (-1, 0), C = (1, 0), B = (0, h), D = (0, -h) as two faces (A, C, B), (C, A, D) sharing
// the diagonal AC. The angles at B and D both have cot = (h^2 - 1) / (2h), so the Delaunay sum of AC is
// (h^2 - 1) / h: negative (AC flips to BD) for h < 1.
struct Kite {
  Eigen::MatrixXd V;
  Eigen::MatrixXi F;
};

Kite kite(double h) {
  Kite k;
  k.V.resize(4, 3);
  k.V << -1, 0, 0, //
      1, 0, 0,     //
      0, h, 0,     //
      0, -h, 0;
  k.F.resize(2, 3);
  k.F << 0, 1, 2, //
      1, 0, 3;
  return k;
}

} // namespace

// One obtuse boundary angle at (0.6, 0.2) over the edge from (0, 0) to (2, 0): the split point is the foot
// of the altitude, x = 0.6, i.e. t = 0.3 measured from (0, 0) and 0.7 from (2, 0). The two new triangles
// have right angles at the foot (cot 0, not obtuse), and the other boundary angles are acute: exactly one
// insertion. A split measured from the wrong end of the edge lands at x = 1.4 and leaves an obtuse angle.
TEST(HandDerived, AsymmetricObtuseBoundarySplitsAtTheFootOfTheAltitude) {
  Eigen::MatrixXd V(3, 3);
  V << 0, 0, 0, //
      2, 0, 0,  //
      0.6, 0.2, 0;
  const Eigen::MatrixXi F = (Eigen::MatrixXi(1, 3) << 0, 1, 2).finished();
  IntrinsicOptions options;
  options.refine_boundary = true;
  const IntrinsicDelaunay idt = intrinsic_delaunay(V, F, options);
  const auto& tri = idt.triangulation;
  ASSERT_EQ(tri.inserted_t.size(), 1);
  EXPECT_EQ(tri.obtuse_boundary_after, 0);
  const double t = tri.inserted_t(0);
  const Eigen::RowVector3d point = (1 - t) * V.row(tri.inserted_on(0, 0)) + t * V.row(tri.inserted_on(0, 1));
  EXPECT_NEAR(point(0), 0.6, kTight);
  EXPECT_NEAR(point(1), 0.0, kTight);
  // The parameter itself, from whichever end the edge is stored.
  EXPECT_NEAR(tri.inserted_on(0, 0) == 0 ? t : 1 - t, 0.3, kTight);
}

// Kite with h = 0.4: AC flips to BD. After the flip the angle at A between AB = (1, 0.4) and AD = (1, -0.4)
// has cot = (1 - 0.16) / 0.8 = 1.05, and so has the one at C: w_BD = (1.05 + 1.05) / 2 = 1.05. BD (length
// 0.8) crosses AC at its midpoint M, so it is traced as two segments of length 0.4, each of weight
// w |e| / |s| = 1.05 * 0.8 / 0.4 = 2.1 (Eq. 11). The boundary edges keep one term: the angle opposite AB at
// D, between DA = (-1, 0.4) and DB = (0, 0.8), has cot = 0.32 / 0.8 = 0.4, so w = 0.2 (all four, by
// symmetry), one segment each of weight 0.2.
TEST(HandDerived, TwoTriangleSegmentWeights) {
  const Kite k = kite(0.4);
  const IntrinsicDelaunay idt = intrinsic_delaunay(k.V, k.F);
  EXPECT_EQ(idt.triangulation.flips, 1);
  const Segments& s = idt.segments;
  ASSERT_EQ(s.weight.size(), 6); // 4 boundary edges + 2 segments of BD
  int crossing = 0, boundary = 0;
  for (Eigen::Index i = 0; i < s.weight.size(); ++i) {
    if (std::abs(s.length(i) - 0.4) < kTight) {
      EXPECT_NEAR(s.weight(i), 2.1, kTight);
      ++crossing;
    } else {
      EXPECT_NEAR(s.length(i), std::sqrt(1 + 0.16), kTight);
      EXPECT_NEAR(s.weight(i), 0.2, kTight);
      ++boundary;
    }
  }
  EXPECT_EQ(crossing, 2);
  EXPECT_EQ(boundary, 4);
}

// The iARAP system matrix of the same kite (vertices A = 0, C = 1, B = 2, D = 3): L = 2 sum_s w_s b_s b_s^T
// (Eq. 16-17: a segment belongs to the rotation cells of both ends of its intrinsic edge). Segments of BD:
// b = (A + C) / 2 - B and D - (A + C) / 2, weight 2.1; boundary edges: b = e_j - e_i, weight 0.2. Summed:
//   L / 2 = [ 1.45  1.05 -1.25 -1.25 ]
//           [ 1.05  1.45 -1.25 -1.25 ]
//           [-1.25 -1.25  2.5   0    ]
//           [-1.25 -1.25  0     2.5  ]
// (rows sum to zero; it is also the cotan Laplacian of the unflipped kite, whose AC weight is -1.05).
TEST(HandDerived, TwoTriangleIarapSystemMatrix) {
  const Kite k = kite(0.4);
  ArapOptions options;
  options.method = ArapMethod::Iarap;
  const ArapData data = arap_precompute(k.V, k.F, (Eigen::VectorXi(1) << 0).finished(), options);
  const Eigen::MatrixXd L = Eigen::MatrixXd(arap_system_matrix(data));
  Eigen::Matrix4d expected;
  expected << 1.45, 1.05, -1.25, -1.25, //
      1.05, 1.45, -1.25, -1.25,         //
      -1.25, -1.25, 2.5, 0,             //
      -1.25, -1.25, 0, 2.5;
  expected *= 2;
  ASSERT_EQ(L.rows(), 4);
  EXPECT_LT((L - expected).cwiseAbs().maxCoeff(), kTight) << L;
}

// The Delaunay test is cot a + cot b < -1e-12 (IntrinsicOptions::delaunay_tolerance). Kites just inside
// and just outside: h = 1 - 5e-10 gives a sum of (h^2 - 1) / h = -1e-9 (flipped); h = 1 - 5e-15 gives
// -1e-14 (kept: round-off on an exact right angle, not a violation). Computing the sum costs ~1e-16 of
// error, far from both.
TEST(HandDerived, FlipThresholdOnNearlyCocircularKites) {
  const Kite flips = kite(1 - 5e-10), keeps = kite(1 - 5e-15);
  EXPECT_EQ(intrinsic_delaunay(flips.V, flips.F).triangulation.flips, 1);
  EXPECT_EQ(intrinsic_delaunay(keeps.V, keeps.F).triangulation.flips, 0);
  // A stricter tolerance than the violation flips the second one too.
  IntrinsicOptions strict;
  strict.delaunay_tolerance = 1e-15;
  EXPECT_EQ(intrinsic_delaunay(keeps.V, keeps.F, strict).triangulation.flips, 1);
}
