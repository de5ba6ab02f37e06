// The face-index range check is written once (src/mesh/face_index_range.h): every function that takes F
// names the first bad entry in the same words, after its own prefix.
#include "iarap/core/errors.h"
#include "iarap/intrinsic/intrinsic_delaunay.h"
#include "iarap/io/write_mesh.h"
#include "iarap/laplacian/mass_matrix.h"
#include "iarap/mesh/repair.h"
#include "iarap/mesh/subdivide.h"
#include "small_meshes.h"
#include "test_support.h"

#include <functional>
#include <gtest/gtest.h>

namespace {

// The octahedron (6 vertices) with face 5's second corner set to `index`.
iarap::test::SmallMesh with_bad_index(int index) {
  iarap::test::SmallMesh m = iarap::test::octahedron();
  m.F(5, 1) = index;
  return m;
}

std::string message_of(const std::function<void()>& call) {
  try {
    call();
  } catch (const iarap::InputError& e) {
    return e.what();
  }
  return "(no InputError)";
}

} // namespace

TEST(FaceIndexRange, EveryCallerNamesTheFaceTheIndexAndTheCount) {
  const std::string path = (iarap::test::temp_dir("face_index_range") / "m.obj").string();
  for (const int index : {6, -1, 1000}) {
    const iarap::test::SmallMesh m = with_bad_index(index);
    const std::string words = "face 5 uses vertex " + std::to_string(index) + "; mesh has 6 vertices";
    Eigen::MatrixXd V_out;
    Eigen::MatrixXi F_out;
    const std::vector<std::pair<std::string, std::function<void()>>> callers = {
        {"repair_mesh: " + words, [&] { iarap::repair_mesh(m.V, m.F); }},
        {"subdivide_midpoint: " + words, [&] { iarap::subdivide_midpoint(m.V, m.F, V_out, F_out); }},
        {words, [&] { iarap::mass_matrix(m.V, m.F, iarap::MassKind::Barycentric); }},
        {words, [&] { iarap::intrinsic_delaunay(m.V, m.F); }},
        {path + ": " + words, [&] { iarap::write_mesh(path, m.V, m.F); }},
    };
    for (const auto& [expected, call] : callers) EXPECT_EQ(message_of(call), expected);
  }
}

// The intrinsic build scans faces in parallel for the first bad one, then names it: a face repeating a
// vertex before a face out of range is the error, a TopologyError.
TEST(FaceIndexRange, IntrinsicNamesTheFirstBadFace) {
  iarap::test::SmallMesh m = with_bad_index(99);
  m.F(2, 1) = m.F(2, 0);
  try {
    iarap::intrinsic_delaunay(m.V, m.F);
    FAIL() << "no error";
  } catch (const iarap::TopologyError& e) {
    EXPECT_STREQ(e.what(), "face 2 repeats a vertex");
  }
}
