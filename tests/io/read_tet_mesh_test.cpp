#include "iarap/io/read_tet_mesh.h"
#include "iarap/io/write_tet_mesh.h"
#include "mesh_file_fixtures.h"

#include <Eigen/Geometry>

using iarap::read_tet_mesh;
using iarap::TetMesh;
using iarap::test::expect_input_error;
using iarap::test::write_temp_file;

namespace {

// Two positive tetrahedra sharing the face (1, 2, 3) (1-based in the files below).
const char* const two_tets_vertices = "0 0 0 7\n1 0 0 7\n0 1 0 7\n0 0 1 7\n1 1 1 7\n";

void expect_two_tets(const TetMesh& m) {
  ASSERT_EQ(m.V.rows(), 5);
  ASSERT_EQ(m.T.rows(), 2);
  EXPECT_EQ(m.V(4, 1), 1.0);
  EXPECT_EQ(m.T.row(0), Eigen::RowVector4i(0, 1, 2, 3));
  EXPECT_TRUE((iarap::tet_signed_volumes(m.V, m.T).array() > 0).all());
}

} // namespace

TEST(ReadTetMesh, MeditKeywordsAnyCaseCommentsAndSectionsReadPast) {
  const std::string path = write_temp_file(
      "two.mesh", std::string("# made by hand\nMeshVersionFormatted 2\nDIMENSION\n3\n\nvertices\n5\n") +
                      two_tets_vertices +
                      "Triangles 1\n1 2 3 0\nTetrahedra 2\n1 2 3 4 1\n2 3 4 5 1\nCorners 1 1\nEnd\n");
  const TetMesh m = read_tet_mesh(path);
  expect_two_tets(m);
  EXPECT_EQ(m.T.row(1), Eigen::RowVector4i(1, 2, 3, 4));
  ASSERT_EQ(m.notes.size(), 2u); // triangles and corners read past
}

TEST(ReadTetMesh, AllNegativeIsReorientedWithANoteMixedSignsAreRefused) {
  const std::string negative =
      write_temp_file("negative.mesh", std::string("MeshVersionFormatted 1\nDimension 3\nVertices 5\n") +
                                           two_tets_vertices + "Tetrahedra 2\n1 2 4 3 0\n2 3 5 4 0\nEnd\n");
  const TetMesh m = read_tet_mesh(negative);
  EXPECT_TRUE((iarap::tet_signed_volumes(m.V, m.T).array() > 0).all());
  ASSERT_EQ(m.notes.size(), 1u);
  EXPECT_NE(m.notes[0].find("reoriented all 2"), std::string::npos);
  const std::string mixed = write_temp_file(
      "mixed.mesh", std::string("MeshVersionFormatted 1\nDimension 3\nVertices 5\n") + two_tets_vertices +
                        "Tetrahedra 3\n1 2 3 4 0\n2 3 4 5 0\n1 2 4 3 0\nEnd\n");
  expect_input_error([&] { read_tet_mesh(mixed); }, {"mixed.mesh:12:", "tetrahedron 2", "inverted"});
}

TEST(ReadTetMesh, MeditErrorsNameFileLineAndTetrahedron) {
  const std::string head =
      std::string("MeshVersionFormatted 1\nDimension 3\nVertices 5\n") + two_tets_vertices;
  const std::string range = write_temp_file("range.mesh", head + "Tetrahedra 2\n1 2 3 4 0\n2 9 4 5 0\nEnd\n");
  expect_input_error([&] { read_tet_mesh(range); },
                     {"range.mesh:11:", "tetrahedron 1", "vertex index 9", "5 vertices"});
  const std::string flat = write_temp_file(
      "flat.mesh", "Dimension 3\nVertices 4\n0 0 0 0\n1 0 0 0\n0 1 0 0\n1 1 0 0\nTetrahedra 1\n1 2 3 4 0\n");
  expect_input_error([&] { read_tet_mesh(flat); }, {"flat.mesh:8:", "tetrahedron 0", "zero volume"});
  const std::string twice = write_temp_file("twice.mesh", head + "Tetrahedra 1\n1 2 2 4 0\n");
  expect_input_error([&] { read_tet_mesh(twice); }, {"twice.mesh:10:", "uses vertex 1 twice"});
  const std::string token = write_temp_file("token.mesh", "Dimension 3\nVertices 1\n0 zero 0 0\n");
  expect_input_error([&] { read_tet_mesh(token); }, {"token.mesh:3:", "bad coordinate 'zero'"});
  const std::string missing = write_temp_file("missing.mesh", head + "End\n");
  expect_input_error([&] { read_tet_mesh(missing); }, {"missing.mesh", "no Tetrahedra section"});
  const std::string truncated = write_temp_file("truncated.mesh", head + "Tetrahedra 2\n1 2 3 4 0\n");
  expect_input_error([&] { read_tet_mesh(truncated); }, {"truncated.mesh:10:", "unexpected end of file"});
  const std::string unknown = write_temp_file("unknown.mesh", head + "Blobs 2\n");
  expect_input_error([&] { read_tet_mesh(unknown); }, {"unknown.mesh:9:", "unknown keyword 'Blobs'"});
}

TEST(ReadTetMesh, TetGenZeroAndOneBasedFromEitherFile) {
  write_temp_file("zero.node", "# points\n5 3 0 0\n0 0 0 0\n1 1 0 0\n2 0 1 0\n3 0 0 1\n4 1 1 1\n");
  const std::string ele = write_temp_file("zero.ele", "2 4 0\n0 0 1 2 3\n1 1 2 3 4 # a comment\n");
  expect_two_tets(read_tet_mesh(ele));
  const std::string node = write_temp_file(
      "one.node", "5 3 1 1\n1 0 0 0 9 1\n2 1 0 0 9 1\n3 0 1 0 9 1\n4 0 0 1 9 1\n5 1 1 1 9 0\n");
  write_temp_file("one.ele", "2 4 0\n1 1 2 3 4\n2 2 3 4 5\n");
  expect_two_tets(read_tet_mesh(node));
  const std::string bad =
      write_temp_file("bad.node", "5 3 0 0\n0 0 0 0\n1 1 0 0\n2 0 1 0\n3 0 0 1\n4 1 1 1\n");
  write_temp_file("bad.ele", "2 4 0\n0 0 1 2 3\n1 1 2 3 5\n");
  expect_input_error([&] { read_tet_mesh(bad); }, {"bad.ele:3:", "vertex index 5", "numbered from 0"});
  const std::string gap = write_temp_file("gap.node", "2 3 0 0\n0 0 0 0\n2 1 0 0\n");
  expect_input_error([&] { read_tet_mesh(gap); }, {"gap.node:3:", "point index 2 where 1 was expected"});
}

TEST(ReadTetMesh, GmshVersion22And41) {
  const std::string v2 = write_temp_file(
      "v2.msh",
      "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$PhysicalNames\n1\n3 1 \"body\"\n$EndPhysicalNames\n"
      "$Nodes\n5\n10 0 0 0\n20 1 0 0\n30 0 1 0\n40 0 0 1\n50 1 1 1\n$EndNodes\n"
      "$Elements\n3\n1 2 2 0 1 10 20 30\n2 4 2 1 1 10 20 30 40\n3 4 2 1 1 20 30 40 50\n$EndElements\n");
  const TetMesh m2 = read_tet_mesh(v2);
  expect_two_tets(m2);
  EXPECT_EQ(m2.notes.size(), 1u); // the triangle
  const std::string v4 = write_temp_file(
      "v4.msh",
      "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Entities\n0 0 0 1\n1 0 0 0 1 1 1 0 0\n$EndEntities\n"
      "$Nodes\n2 5 1 5\n3 1 0 3\n1\n2\n3\n0 0 0\n1 0 0\n0 1 0\n3 1 0 2\n4\n5\n0 0 1\n1 1 1\n$EndNodes\n"
      "$Elements\n1 2 1 2\n3 1 4 2\n1 1 2 3 4\n2 2 3 4 5\n$EndElements\n");
  expect_two_tets(read_tet_mesh(v4));
  const std::string unknown_node =
      write_temp_file("tag.msh", "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n1\n1 0 0 0\n$EndNodes\n"
                                 "$Elements\n1\n1 4 0 1 2 3 4\n$EndElements\n");
  expect_input_error([&] { read_tet_mesh(unknown_node); }, {"tag.msh:10:", "node tag 2 is not in $Nodes"});
  const std::string binary = write_temp_file("binary.msh", "$MeshFormat\n4.1 1 8\n");
  expect_input_error([&] { read_tet_mesh(binary); }, {"binary.msh:2:", "binary"});
}

TEST(WriteTetMesh, RoundTripIsExact) {
  TetMesh m;
  m.V.resize(5, 3);
  m.V << 0, 0, 0, 1.0 / 3.0, 1e-300, 0, 0, 2.0 / 3.0, 0, 0, 0, 0.1, 1, 1, 1 + 1e-15;
  m.T.resize(2, 4);
  m.T << 0, 1, 2, 3, 1, 2, 3, 4;
  const std::string path = (iarap::test::temp_dir("io") / "round.mesh").string();
  iarap::write_tet_mesh(path, m.V, m.T);
  const TetMesh back = read_tet_mesh(path);
  EXPECT_EQ(back.V, m.V);
  EXPECT_EQ(back.T, m.T);
  expect_input_error([&] { iarap::write_tet_mesh(path, m.V, Eigen::MatrixXi::Constant(1, 4, 5)); },
                     {"round.mesh", "tetrahedron 0 uses vertex 5"});
  expect_input_error([&] { iarap::write_tet_mesh(path + ".obj", m.V, m.T); }, {"writable: .mesh"});
}

TEST(TetBoundaryFaces, OutwardFacesOfOneTetAndNoSharedFace) {
  Eigen::MatrixXd V(5, 3);
  V << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 1, 1, 1;
  Eigen::MatrixXi T(2, 4);
  T << 0, 1, 2, 3, 1, 2, 3, 4;
  const Eigen::MatrixXi F = iarap::tet_boundary_faces(T);
  ASSERT_EQ(F.rows(), 6); // 8 faces, the shared one twice
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    const int t = f < 3 ? 0 : 1;
    Eigen::RowVector3d centroid = Eigen::RowVector3d::Zero();
    for (int k = 0; k < 4; ++k) centroid += V.row(T(t, k)) / 4.0;
    const Eigen::Vector3d a = V.row(F(f, 0)), b = V.row(F(f, 1)), c = V.row(F(f, 2));
    EXPECT_GT((b - a).cross(c - a).dot(a - centroid.transpose()), 0.0) << "face " << f;
  }
}
