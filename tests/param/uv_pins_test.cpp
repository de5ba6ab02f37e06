// arap_parameterize with pins (ParamOptions::pins): held exactly, one or two pins moving the unpinned map
// by a similarity (so a flat disk pinned at the images of a rigid motion maps by that motion), three or
// more shaping the start, pins inside a circular boundary, the fold refused flip-free, and bad pins.
#include "iarap/param/arap_parameterize.h"

#include "iarap/core/errors.h"
#include "iarap/param/disk_mesh.h"
#include "param/disk_meshes.h"
#include "test_support.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

namespace iarap {
namespace {

UvPins make_pins(std::initializer_list<int> vertices, std::initializer_list<Eigen::RowVector2d> uv) {
  UvPins pins;
  pins.vertices.resize(static_cast<Eigen::Index>(vertices.size()));
  pins.uv.resize(static_cast<Eigen::Index>(uv.size()), 2);
  Eigen::Index p = 0;
  for (int v : vertices) pins.vertices(p++) = v;
  p = 0;
  for (const Eigen::RowVector2d& row : uv) pins.uv.row(p++) = row;
  return pins;
}

// The rigid motion of the plane used below: rotation by 0.7 rad, then a shift.
Eigen::RowVector2d moved(const Eigen::RowVector3d& x) {
  const double c = std::cos(0.7), s = std::sin(0.7);
  return {c * x(0) - s * x(1) + 3, s * x(0) + c * x(1) - 2};
}

void expect_pins_held(const ParamResult& result, const UvPins& pins) {
  for (Eigen::Index p = 0; p < pins.size(); ++p)
    EXPECT_EQ(result.UV.row(pins.vertices(p)), pins.uv.row(p)) << "pin " << p;
}

TEST(UvPins, TwoPinsOnARigidMotionGiveThatMotion) {
  // A flat disk's best map is an isometry; pinned at two vertices' images under a rigid motion, the only
  // zero-energy map holding them is that motion of (x, y). The iteration converges to it to ~1e-12
  // (energy ~1e-24); checked at 1e-9 of the disk's radius 1.
  const test::TestMesh disk = test::flat_disk(5, 14);
  const int a = 0, b = static_cast<int>(disk.V.rows()) - 1;
  ParamOptions options;
  options.pins = make_pins({a, b}, {moved(disk.V.row(a)), moved(disk.V.row(b))});
  options.solve.tolerance = 0;
  options.solve.max_iterations = 200;
  const ParamResult result = arap_parameterize(disk.V, disk.F, options);
  expect_pins_held(result, options.pins);
  EXPECT_EQ(result.report.pinned, 2);
  for (Eigen::Index v = 0; v < disk.V.rows(); ++v)
    EXPECT_LT((result.UV.row(v) - moved(disk.V.row(v))).norm(), 1e-9) << "vertex " << v;
}

TEST(UvPins, OnePinTranslatesTheDefaultMap) {
  // The energy is translation invariant and the default pins the first boundary vertex: a pin elsewhere
  // gives the same map up to a shift (the same operations on shifted numbers: equal to rounding).
  const test::TestMesh cap = test::spherical_cap(6, 18, 0.5 * M_PI);
  const ParamResult free = arap_parameterize(cap.V, cap.F);
  ParamOptions options;
  options.pins = make_pins({5}, {Eigen::RowVector2d(10, -4)});
  const ParamResult pinned = arap_parameterize(cap.V, cap.F, options);
  expect_pins_held(pinned, options.pins);
  const Eigen::RowVector2d shift = pinned.UV.row(5) - free.UV.row(5);
  EXPECT_LT(((pinned.UV.rowwise() - shift) - free.UV).cwiseAbs().maxCoeff(), 1e-9);
  EXPECT_NEAR(pinned.report.distortion.energy, free.report.distortion.energy,
              1e-8 * free.report.distortion.energy);
}

TEST(UvPins, ThreePinsStretchAFlatSquare) {
  // The unit square's corners (0,0), (1,0), (0,1) pinned onto a 2 x 1 rectangle: no isometry holds them,
  // the result is flip-free, holds the pins exactly, and lowers the energy from its LSCM start.
  const test::TestMesh square = test::flat_square(8);
  auto corner = [&square](double x, double y) {
    for (Eigen::Index v = 0; v < square.V.rows(); ++v)
      if (square.V(v, 0) == x && square.V(v, 1) == y) return static_cast<int>(v);
    return -1;
  };
  ParamOptions options;
  options.pins = make_pins({corner(0, 0), corner(1, 0), corner(0, 1)},
                           {Eigen::RowVector2d(0, 0), Eigen::RowVector2d(2, 0), Eigen::RowVector2d(0, 1)});
  const ParamResult result = arap_parameterize(square.V, square.F, options);
  expect_pins_held(result, options.pins);
  EXPECT_EQ(result.report.distortion.flipped, 0);
  EXPECT_GT(result.report.distortion.energy,
            0.1); // a stretch by 2 costs: per unit area ||diag(2,1)-I||^2 = 1
  EXPECT_LT(result.report.distortion.energy, result.report.solve.initial_energy);
}

TEST(UvPins, MirroredPinsFoldAndAreRefusedFlipFree) {
  // Three pins at the mirror images of their vertices: LSCM holding them folds triangles, which no
  // flip-free step can undo. Refused by default; with allow_flips the plain iteration runs and holds them.
  const test::TestMesh square = test::flat_square(6);
  const int a = 0, b = 6, c = static_cast<int>(square.V.rows()) - 1;
  auto mirror = [&square](int v) { return Eigen::RowVector2d(-square.V(v, 0), square.V(v, 1)); };
  ParamOptions options;
  options.pins = make_pins({a, b, c}, {mirror(a), mirror(b), mirror(c)});
  try {
    arap_parameterize(square.V, square.F, options);
    FAIL() << "mirrored pins were accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("folds"), std::string::npos) << e.what();
  }
  options.allow_flips = true;
  const ParamResult result = arap_parameterize(square.V, square.F, options);
  expect_pins_held(result, options.pins);
  EXPECT_GT(result.report.distortion.flipped, 0);
}

TEST(UvPins, InnerPinWithACircularBoundary) {
  // The polar disk's centre (vertex 0) pinned off the circle's centre: held, the boundary stays on the
  // circle, no flip (the pin is well inside).
  const test::TestMesh cap = test::spherical_cap(6, 18, 0.4 * M_PI);
  const DiskMesh disk = prepare_disk(cap.V, cap.F);
  ParamOptions options;
  options.boundary = ParamBoundary::Circle;
  options.init = ParamInit::Harmonic;
  options.pins = make_pins({0}, {Eigen::RowVector2d(0.1, 0.05)});
  const ParamResult result = arap_parameterize(cap.V, cap.F, options);
  expect_pins_held(result, options.pins);
  EXPECT_EQ(result.report.pinned, static_cast<int>(disk.boundary.size()) + 1);
  EXPECT_EQ(result.report.distortion.flipped, 0);
  // A boundary vertex cannot be pinned there: the circle holds it.
  options.pins = make_pins({disk.boundary[0]}, {Eigen::RowVector2d(0, 0)});
  EXPECT_THROW(arap_parameterize(cap.V, cap.F, options), InputError);
}

TEST(UvPins, RefusesBadPins) {
  const test::TestMesh disk = test::flat_disk(2, 8);
  const auto n = static_cast<int>(disk.V.rows());
  const Eigen::RowVector2d origin(0, 0), one(1, 0);
  for (const UvPins& pins :
       {make_pins({n}, {origin}), make_pins({-1}, {origin}), make_pins({1, 1}, {origin, one}),
        make_pins({1, 2}, {origin, Eigen::RowVector2d(NAN, 0)}), make_pins({1, 2}, {origin, origin}),
        make_pins({1, 2}, {origin})}) {
    ParamOptions options;
    options.pins = pins;
    EXPECT_THROW(arap_parameterize(disk.V, disk.F, options), InputError);
  }
}

} // namespace
} // namespace iarap
