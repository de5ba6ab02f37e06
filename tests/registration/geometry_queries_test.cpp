// The k-d tree, closest points on triangles and the normals registration is built on, each against a brute
// force or an exact answer.
#include "iarap/core/errors.h"
#include "iarap/registration/closest_surface_point.h"
#include "iarap/registration/point_index.h"
#include "iarap/registration/surface_normals.h"

#include <gtest/gtest.h>

#include <random>

namespace iarap {
namespace {

TEST(PointIndex, NearestMatchesBruteForce) {
  std::mt19937 random(7);
  std::uniform_real_distribution<double> uniform(-1, 1);
  Eigen::MatrixXd P(500, 3);
  for (Eigen::Index i = 0; i < P.size(); ++i) P(i) = uniform(random);
  const PointIndex index(P);
  std::vector<Eigen::Index> near;
  std::vector<double> squared;
  for (int trial = 0; trial < 100; ++trial) {
    const Eigen::Vector3d q(uniform(random), uniform(random), uniform(random));
    Eigen::Index best = 0;
    (P.rowwise() - q.transpose()).rowwise().squaredNorm().minCoeff(&best);
    const auto [found, d2] = index.nearest(q);
    EXPECT_EQ(found, best);
    EXPECT_DOUBLE_EQ(d2, (P.row(best) - q.transpose()).squaredNorm());
    index.nearest_k(q, 5, near, squared);
    ASSERT_EQ(near.size(), 5u);
    EXPECT_EQ(near[0], best);
    for (std::size_t k = 1; k < near.size(); ++k) EXPECT_LE(squared[k - 1], squared[k]);
  }
}

TEST(ClosestPointOnTriangle, InteriorEdgeAndCorner) {
  const Eigen::Vector3d a(0, 0, 0), b(1, 0, 0), c(0, 1, 0);
  Eigen::Vector3d bary;
  // Above the interior: the orthogonal projection.
  EXPECT_TRUE(closest_point_on_triangle({0.2, 0.3, 5}, a, b, c, bary).isApprox(Eigen::Vector3d(0.2, 0.3, 0)));
  EXPECT_TRUE(bary.isApprox(Eigen::Vector3d(0.5, 0.2, 0.3)));
  // Beyond the hypotenuse: its closest point.
  EXPECT_TRUE(closest_point_on_triangle({1, 1, 0}, a, b, c, bary).isApprox(Eigen::Vector3d(0.5, 0.5, 0)));
  // Beyond a corner.
  EXPECT_TRUE(closest_point_on_triangle({-1, -2, 3}, a, b, c, bary).isApprox(a));
  EXPECT_TRUE(bary.isApprox(Eigen::Vector3d(1, 0, 0)));
}

TEST(SurfaceNormals, PcaNormalsOfASphereAreRadial) {
  std::mt19937 random(3);
  std::normal_distribution<double> gauss(0, 1);
  Eigen::MatrixXd P(2000, 3);
  for (Eigen::Index i = 0; i < P.rows(); ++i) {
    const Eigen::Vector3d x(gauss(random), gauss(random), gauss(random));
    P.row(i) = x.normalized().transpose();
  }
  const Eigen::MatrixXd N = estimate_point_normals(P, PointIndex(P), 12, "sphere");
  for (Eigen::Index i = 0; i < P.rows(); ++i) EXPECT_GT(N.row(i).dot(P.row(i)), 0.98) << "point " << i;
}

TEST(SurfaceNormals, AreaWeightedVertexNormalsOfATetrahedronCorner) {
  Eigen::MatrixXd V(4, 3);
  V << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1;
  Eigen::MatrixXi F(3, 3);
  F << 0, 2, 1, 0, 3, 2, 0, 1, 3; // the three faces at the origin, outward
  const Eigen::MatrixXd N = area_weighted_vertex_normals(V, F);
  EXPECT_TRUE(N.row(0).isApprox(-Eigen::RowVector3d::Ones().normalized()));
}

TEST(SurfaceNormals, TooFewPointsIsAnErrorNamingTheSource) {
  const Eigen::MatrixXd P = Eigen::MatrixXd::Random(2, 3);
  try {
    estimate_point_normals(P, PointIndex(P), 12, "scan.xyz");
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("scan.xyz: 2 points; need at least 3"), std::string::npos)
        << e.what();
  }
}

} // namespace
} // namespace iarap
