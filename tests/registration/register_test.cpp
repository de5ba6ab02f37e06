// Non-rigid ICP finds a known ARAP deformation again from a noisy point cloud, far closer than the
// deformation the landmarks alone give; bad input is refused naming the element.
#include "iarap/core/errors.h"
#include "iarap/registration/register.h"
#include "registration_fixtures.h"

#include <gtest/gtest.h>

#include <fstream>
#include <functional>

namespace iarap {
namespace {

using test::mean_row_distance;

// Every (n / count)-th vertex, with its position in the known answer.
RegistrationLandmarks spread_landmarks(const Eigen::MatrixXd& U, int count) {
  RegistrationLandmarks l;
  l.vertices.resize(count);
  l.vertex_targets.resize(count, 3);
  const auto stride = static_cast<int>(U.rows() / count);
  for (int k = 0; k < count; ++k) {
    l.vertices(k) = k * stride;
    l.vertex_targets.row(k) = U.row(k * stride);
  }
  return l;
}

TEST(Register, FindsAKnownDeformationFromANoisyPointCloud) {
  const test::OneThread one_thread;
  const test::KnownDeformation known = test::bunny_deformation();
  const Eigen::MatrixXd& V = known.mesh.V;
  const Eigen::MatrixXi& F = known.mesh.F;
  const RegistrationTarget target = make_registration_target(
      sample_surface(known.U, F, 12000, 46, 0.001 * known.diagonal), {}, {}, "samples");
  const RegistrationLandmarks landmarks = spread_landmarks(known.U, 12);

  ArapData data = arap_precompute(V, F, landmarks.vertices);
  Eigen::MatrixXd landmarks_only = V;
  arap_solve(data, landmarks.vertex_targets, landmarks_only);
  const double landmarks_error = mean_row_distance(landmarks_only, known.U) / known.diagonal;

  const RegistrationResult fit = register_to_target(V, F, target, landmarks);
  const double fit_error = mean_row_distance(fit.U, known.U) / known.diagonal;
  std::cout << "mean vertex error / diagonal: landmarks only " << landmarks_error << ", registered "
            << fit_error << " (" << fit.report.rounds.size() << " rounds, final mean distance "
            << fit.report.final_distance.mean << ")\n";
  EXPECT_LT(fit_error, 0.5 * landmarks_error); // measured: 0.0024 against 0.0074
  EXPECT_LT(fit.report.final_distance.mean, fit.report.initial_distance.mean);
  ASSERT_EQ(fit.U.rows(), V.rows());
}

std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

TEST(Register, BadTargetsAreRefusedNamingTheFileAndElement) {
  EXPECT_NE(error_of([] {
              make_registration_target(Eigen::MatrixXd(0, 3), {}, {}, "empty.xyz");
            }).find("empty.xyz: the target has no point"),
            std::string::npos);
  Eigen::MatrixXd P = Eigen::MatrixXd::Random(10, 3);
  P(5, 1) = std::nan("");
  EXPECT_NE(error_of([&] {
              make_registration_target(P, {}, {}, "scan.ply");
            }).find("scan.ply: target point 5 is not finite"),
            std::string::npos);
  EXPECT_NE(error_of([] {
              make_registration_target(Eigen::MatrixXd::Random(10, 3), {},
                                       (Eigen::MatrixXi(1, 3) << 0, 1, 12).finished(), "scan.off");
            }).find("scan.off: target face 0 uses point 12; the target has 10"),
            std::string::npos);
  EXPECT_NE(error_of([] {
              make_registration_target(Eigen::MatrixXd::Random(2, 3), {}, {}, "two.xyz");
            }).find("need at least 3 points to estimate normals"),
            std::string::npos);

  const auto dir = test::temp_dir("register_bad");
  const std::string bad = (dir / "bad.xyz").string();
  std::ofstream(bad) << "0 0 0\n1 0 0\n0 1 nan\n";
  EXPECT_NE(error_of([&] { read_registration_target(bad); }).find(bad + ":3: non-finite z coordinate"),
            std::string::npos)
      << error_of([&] { read_registration_target(bad); });
  const std::string mixed = (dir / "mixed.xyz").string();
  std::ofstream(mixed) << "# a comment\n0 0 0\n1 0 0 0 0 1\n";
  EXPECT_NE(error_of([&] { read_registration_target(mixed); }).find(mixed + ":3: 6 values, but line 2 has 3"),
            std::string::npos)
      << error_of([&] { read_registration_target(mixed); });
}

// A vertex-only OBJ is a point cloud (PCA normals, compared up to sign), an OFF with faces a mesh target
// (area-weighted vertex normals), an .xyz with normals keeps them.
TEST(Register, TargetFilesOfEachKind) {
  const auto dir = test::temp_dir("register_targets");
  const std::string obj = (dir / "points.obj").string(), xyz = (dir / "oriented.xyz").string();
  std::ofstream(obj) << "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0.1\n";
  std::ofstream(xyz) << "0 0 0 0 0 2\n1 0 0 0 0 1\n0 1 0 0 0 1\n";
  const RegistrationTarget cloud = read_registration_target(obj);
  EXPECT_EQ(cloud.points.rows(), 4);
  EXPECT_EQ(cloud.faces.rows(), 0);
  EXPECT_FALSE(cloud.oriented);
  const RegistrationTarget oriented = read_registration_target(xyz);
  EXPECT_TRUE(oriented.oriented);
  EXPECT_TRUE(oriented.normals.row(0).isApprox(Eigen::RowVector3d(0, 0, 1)));
  const RegistrationTarget mesh = read_registration_target(test::data_path("bunny.off"));
  EXPECT_EQ(mesh.faces.rows(), 6966);
  EXPECT_TRUE(mesh.oriented);
  const std::string empty = (dir / "empty.xyz").string();
  std::ofstream(empty) << "# nothing\n";
  EXPECT_NE(error_of([&] { read_registration_target(empty); }).find(empty + ": the point cloud has no point"),
            std::string::npos);
}

TEST(Register, LandmarksOutOfRangeAreRefusedNamingThem) {
  const MeshData mesh = read_mesh(test::data_path("bunny.off"));
  const RegistrationTarget target = make_registration_target(mesh.V, {}, mesh.F, "bunny");
  RegistrationLandmarks l;
  l.vertices = Eigen::VectorXi::Constant(1, 99999);
  l.vertex_targets = Eigen::MatrixXd::Zero(1, 3);
  EXPECT_NE(error_of([&] {
              register_to_target(mesh.V, mesh.F, target, l);
            }).find("landmark 0: vertex 99999 out of range; the source has 3485 vertices"),
            std::string::npos);
  RegistrationLandmarks b;
  b.faces = Eigen::VectorXi::Constant(1, 7000);
  b.barycentric = Eigen::MatrixXd::Constant(1, 3, 1.0 / 3);
  b.face_targets = Eigen::MatrixXd::Zero(1, 3);
  EXPECT_NE(error_of([&] {
              register_to_target(mesh.V, mesh.F, target, b);
            }).find("face landmark 0: face 7000 out of range; the source has 6966 faces"),
            std::string::npos);
}

} // namespace
} // namespace iarap
