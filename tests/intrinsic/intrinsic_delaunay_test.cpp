#include "iarap/intrinsic/intrinsic_delaunay.h"

#include "iarap/core/errors.h"
#include "iarap/io/read_mesh.h"
#include "iarap/mesh/edge_topology.h"
#include "intrinsic/mesh_generators.h"
#include "test_support.h"

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <map>
#include <set>
#include <string>

using namespace iarap;
using iarap::test::TestMesh;

namespace {

// The invariants every intrinsic Delaunay triangulation must satisfy (issue 4's list). Returns the
// largest number of segments of one edge.
int expect_invariants(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, const IntrinsicDelaunay& idt,
                      const std::string& name) {
  const auto& tri = idt.triangulation;
  const auto& seg = idt.segments;
  const auto& tr = idt.traces;
  const EdgeTopology topo = edge_topology(F, static_cast<int>(V.rows()));
  // Each inserted boundary point splits one face and one edge and adds one interior edge, which keeps
  // the Euler characteristic.
  const Eigen::Index inserted = tri.inserted_t.size();
  EXPECT_EQ(tri.F.rows(), F.rows() + inserted) << name;
  EXPECT_EQ(tri.E.rows(), topo.E.rows() + 2 * inserted) << name;
  EXPECT_EQ(tri.non_delaunay_after, 0) << name;
  int max_segments = 0;
  int failures = 0;
  // Corner angles and areas are kept up to date through the flips (two atan2 per flip, the other angles
  // as sums and differences), so compare them with a fresh computation from the final lengths. Each flip
  // adds ~1e-16 rad of rounding to a corner; 1e-9 rad leaves room for 10^6 flips at one vertex.
  Eigen::VectorXd angle_sum = Eigen::VectorXd::Zero(V.rows() + inserted);
  for (int f = 0; f < tri.F.rows() && failures < 5; ++f) {
    double l[3];
    for (int k = 0; k < 3; ++k) l[k] = tri.length(tri.FE(f, k)); // side opposite corner k
    const double s = 0.5 * (l[0] + l[1] + l[2]);
    const double area = std::sqrt(std::max(s * (s - l[0]) * (s - l[1]) * (s - l[2]), 0.0));
    EXPECT_NEAR(tri.face_area(f), area, 1e-9 * (l[0] * l[0] + l[1] * l[1] + l[2] * l[2]))
        << name << " face " << f;
    for (int k = 0; k < 3; ++k) {
      const double a = l[k], b = l[(k + 1) % 3], c = l[(k + 2) % 3];
      const double expected = std::atan2(4.0 * area, b * b + c * c - a * a);
      if (std::abs(tri.corner_angle(f, k) - expected) > 1e-9) {
        ADD_FAILURE() << name << ": face " << f << " corner " << k << " angle " << tri.corner_angle(f, k)
                      << " vs " << expected << " from its lengths";
        ++failures;
      }
      angle_sum(tri.F(f, k)) += tri.corner_angle(f, k);
    }
  }
  // Flips keep each vertex's total angle: compare with the input's (unmollified meshes only).
  if (tri.mollify_delta == 0.0) {
    Eigen::VectorXd input_sum = Eigen::VectorXd::Zero(V.rows());
    for (int f = 0; f < F.rows(); ++f)
      for (int k = 0; k < 3; ++k) {
        const Eigen::Vector3d u = V.row(F(f, (k + 1) % 3)) - V.row(F(f, k)),
                              w = V.row(F(f, (k + 2) % 3)) - V.row(F(f, k));
        input_sum(F(f, k)) += std::atan2(u.cross(w).norm(), u.dot(w));
      }
    for (int v = 0; v < V.rows() && failures < 5; ++v)
      if (std::abs(angle_sum(v) - input_sum(v)) > 1e-8) {
        ADD_FAILURE() << name << ": vertex " << v << " angle sum " << angle_sum(v) << " vs input "
                      << input_sum(v);
        ++failures;
      }
  }
  for (int e = 0; e < tri.E.rows() && failures < 5; ++e) {
    // Delaunay: cot a + cot b >= 0 up to the flip tolerance (cotangents are scale-free).
    if (!tri.is_boundary(e) && 2 * tri.cot_weight(e) < -1e-9) {
      ADD_FAILURE() << name << ": edge " << e << " not Delaunay, cot sum " << 2 * tri.cot_weight(e);
      ++failures;
    }
    const int p0 = tr.start[e], p1 = tr.start[e + 1];
    EXPECT_GE(p1 - p0, 2);
    // End points: the input vertex itself, or the inserted boundary point's input edge and parameter.
    for (const auto& [p, v] :
         {std::pair<int, int>{p0, tri.E(e, 0)}, std::pair<int, int>{p1 - 1, tri.E(e, 1)}}) {
      if (v < tri.num_input_vertices) {
        EXPECT_EQ(tr.a[p], v);
        EXPECT_EQ(tr.c[p], -1);
      } else {
        const int q = v - tri.num_input_vertices;
        EXPECT_EQ(tr.a[p], tri.inserted_on(q, 0));
        EXPECT_EQ(tr.c[p], tri.inserted_on(q, 1));
        EXPECT_EQ(tr.t[p], tri.inserted_t(q));
      }
    }
    double traced = 0.0;
    for (int s = seg.edge_start(e); s < seg.edge_start(e + 1); ++s) {
      traced += seg.length(s);
      // Both ends of the segment lie on its carrying input face.
      const int g = seg.face(s);
      const int m = p0 + (s - seg.edge_start(e));
      for (int p : {m, m + 1})
        for (int v : {tr.a[p], tr.c[p]}) {
          if (v < 0) continue;
          if (v != F(g, 0) && v != F(g, 1) && v != F(g, 2)) {
            ADD_FAILURE() << name << ": point " << p << " of edge " << e << " is not on face " << g;
            ++failures;
          }
        }
      EXPECT_NEAR(seg.b_value.row(s).sum(), 0.0, 1e-14) << name << " segment " << s;
      EXPECT_LE((seg.b_value.row(s).array() != 0.0).count(), 3);
    }
    max_segments = std::max(max_segments, seg.edge_start(e + 1) - seg.edge_start(e));
    // With mollification the layout uses lengths longer by delta than the extrinsic ones.
    if (tri.mollify_delta == 0.0 && std::abs(traced - tri.length(e)) > 1e-9 * tri.length(e)) {
      ADD_FAILURE() << name << ": edge " << e << " traced length " << traced << " vs intrinsic "
                    << tri.length(e);
      ++failures;
    }
  }
  return max_segments;
}

// Independent planar check: every intrinsic face's circumcircle (from the input points) holds no vertex.
void expect_planar_delaunay(const Eigen::MatrixXd& V, const IntrinsicDelaunay& idt, const std::string& name) {
  const auto& tri = idt.triangulation;
  const double scale = (V.colwise().maxCoeff() - V.colwise().minCoeff()).norm();
  int failures = 0;
  for (int f = 0; f < tri.F.rows() && failures < 5; ++f) {
    const Eigen::Vector2d a = V.row(tri.F(f, 0)).head<2>(), b = V.row(tri.F(f, 1)).head<2>(),
                          c = V.row(tri.F(f, 2)).head<2>();
    const double d = 2 * (a.x() * (b.y() - c.y()) + b.x() * (c.y() - a.y()) + c.x() * (a.y() - b.y()));
    const Eigen::Vector2d centre((a.squaredNorm() * (b.y() - c.y()) + b.squaredNorm() * (c.y() - a.y()) +
                                  c.squaredNorm() * (a.y() - b.y())) /
                                     d,
                                 (a.squaredNorm() * (c.x() - b.x()) + b.squaredNorm() * (a.x() - c.x()) +
                                  c.squaredNorm() * (b.x() - a.x())) /
                                     d);
    const double radius = (a - centre).norm();
    for (int v = 0; v < V.rows(); ++v) {
      if (v == tri.F(f, 0) || v == tri.F(f, 1) || v == tri.F(f, 2)) continue;
      if ((V.row(v).head<2>().transpose() - centre).norm() < radius - 1e-9 * scale) {
        ADD_FAILURE() << name << ": vertex " << v << " inside the circumcircle of intrinsic face " << f;
        ++failures;
        break;
      }
    }
  }
  // Every traced edge is the straight segment between its end points.
  for (int e = 0; e < tri.E.rows(); ++e) {
    const Eigen::Vector3d p = V.row(tri.E(e, 0)), q = V.row(tri.E(e, 1));
    EXPECT_NEAR(tri.length(e), (q - p).norm(), 1e-12 * scale) << name << " edge " << e;
    for (int k = idt.traces.start[e]; k < idt.traces.start[e + 1]; ++k) {
      const int a = idt.traces.a[k], c = idt.traces.c[k];
      const double t = idt.traces.t[k];
      const Eigen::Vector3d x =
          c < 0 ? Eigen::Vector3d(V.row(a)) : Eigen::Vector3d((1 - t) * V.row(a) + t * V.row(c));
      const double off_line = ((x - p).cross(q - p)).norm() / (q - p).norm();
      EXPECT_LT(off_line, 1e-10 * scale) << name << " edge " << e << " point " << k;
    }
  }
}

// Every traced point of a flat mesh lies on the straight line between its edge's end points.
void expect_planar_delaunay_edges_straight(const Eigen::MatrixXd& V, const IntrinsicDelaunay& idt,
                                           const std::string& name) {
  const auto& tri = idt.triangulation;
  const auto& tr = idt.traces;
  const double scale = (V.colwise().maxCoeff() - V.colwise().minCoeff()).norm();
  auto point = [&](int k) {
    const int a = tr.a[k], c = tr.c[k];
    return c < 0 ? Eigen::Vector3d(V.row(a)) : Eigen::Vector3d((1 - tr.t[k]) * V.row(a) + tr.t[k] * V.row(c));
  };
  for (int e = 0; e < tri.E.rows(); ++e) {
    const Eigen::Vector3d p = point(tr.start[e]), q = point(tr.start[e + 1] - 1);
    EXPECT_NEAR(tri.length(e), (q - p).norm(), 1e-12 * scale) << name << " edge " << e;
    for (int k = tr.start[e]; k < tr.start[e + 1]; ++k)
      EXPECT_LT(((point(k) - p).cross(q - p)).norm() / (q - p).norm(), 1e-10 * scale)
          << name << " edge " << e;
  }
}

} // namespace

TEST(IntrinsicDelaunay, DelaunayGridNeedsNoFlips) {
  const TestMesh m = iarap::test::planar_grid(6);
  const IntrinsicDelaunay idt = intrinsic_delaunay(m.V, m.F);
  EXPECT_EQ(idt.triangulation.flips, 0);
  EXPECT_EQ(idt.segments.edge.size(), idt.triangulation.E.rows()); // one segment per edge
  for (int s = 0; s < idt.segments.edge.size(); ++s) {
    EXPECT_EQ((idt.segments.b_value.row(s).array() != 0.0).count(), 2);
    EXPECT_NEAR(idt.segments.weight(s), idt.triangulation.cot_weight(idt.segments.edge(s)), 1e-15);
    EXPECT_EQ(idt.triangulation.original_edge(s), s);
  }
  expect_invariants(m.V, m.F, idt, "grid");
}

TEST(IntrinsicDelaunay, DelaunaySharedMeshesNeedNoFlips) {
  for (const std::string name : {"cube.obj", "bumpy-cube.obj"}) {
    const std::string path = iarap::test::shared_mesh_in_loop(name);
    if (path.empty()) continue;
    const MeshData mesh = read_mesh(path);
    const IntrinsicDelaunay idt = intrinsic_delaunay(mesh.V, mesh.F);
    EXPECT_EQ(idt.triangulation.flips, 0) << name;
    EXPECT_EQ(idt.segments.edge.size(), idt.triangulation.E.rows()) << name;
    for (int s = 0; s < idt.segments.edge.size(); ++s)
      ASSERT_EQ((idt.segments.b_value.row(s).array() != 0.0).count(), 2) << name;
  }
}

TEST(IntrinsicDelaunay, BundledBunny) {
  const MeshData mesh = read_mesh(iarap::test::data_path("bunny.off"));
  const IntrinsicDelaunay idt = intrinsic_delaunay(mesh.V, mesh.F);
  EXPECT_GT(idt.triangulation.non_delaunay_before, 0);
  EXPECT_GT(idt.triangulation.flips, 0);
  EXPECT_EQ(idt.triangulation.mollify_delta, 0.0);
  const int max_segments = expect_invariants(mesh.V, mesh.F, idt, "bunny");
  EXPECT_GE(max_segments, 2);
  // Every weight of a closed intrinsic Delaunay mesh is non-negative (Eq. 11 keeps the sign of w_ij).
  EXPECT_GE(idt.segments.weight.minCoeff(), -1e-12);
}

TEST(IntrinsicDelaunay, MatrixBIsOptional) {
  const MeshData mesh = read_mesh(iarap::test::data_path("bunny.off"));
  IntrinsicOptions options;
  const IntrinsicDelaunay with_B = intrinsic_delaunay(mesh.V, mesh.F, options);
  options.assemble_B = false;
  const IntrinsicDelaunay without_B = intrinsic_delaunay(mesh.V, mesh.F, options);
  EXPECT_EQ(without_B.segments.B.nonZeros(), 0);
  EXPECT_EQ(with_B.segments.B.rows(), with_B.segments.edge.size());
  EXPECT_EQ(with_B.segments.B.cols(), mesh.V.rows());
  // Everything else is the same, bit for bit.
  EXPECT_EQ(without_B.segments.b_index, with_B.segments.b_index);
  EXPECT_EQ(without_B.segments.b_value, with_B.segments.b_value);
  EXPECT_EQ(without_B.segments.weight, with_B.segments.weight);
  // Row s of B is b_s.
  const Eigen::MatrixXd B = Eigen::MatrixXd(with_B.segments.B);
  for (int s = 0; s < with_B.segments.edge.size(); s += 97) {
    Eigen::VectorXd row = Eigen::VectorXd::Zero(mesh.V.rows());
    for (int k = 0; k < 3; ++k) row(with_B.segments.b_index(s, k)) += with_B.segments.b_value(s, k);
    EXPECT_EQ((B.row(s).transpose() - row).cwiseAbs().maxCoeff(), 0.0) << "segment " << s;
  }
}

namespace {
// A flat strip whose boundary triangles are obtuse: the top row is shifted so that the Delaunay
// triangle of every bottom edge has its apex inside the edge's diametral circle.
TestMesh obtuse_strip() {
  TestMesh m;
  const int n = 8;
  m.V.resize(2 * (n + 1), 3);
  for (int i = 0; i <= n; ++i) {
    m.V.row(i) << i, 0, 0;
    m.V.row(n + 1 + i) << i + 0.5, 0.2, 0;
  }
  m.F.resize(2 * n, 3);
  for (int i = 0; i < n; ++i) {
    m.F.row(2 * i) << i, i + 1, n + 1 + i;
    m.F.row(2 * i + 1) << i + 1, n + 2 + i, n + 1 + i;
  }
  return m;
}
} // namespace

// Without traces the segments come from the compact traces (points of flipped edges only): they must be
// the same bit for bit, on a non-Delaunay closed mesh and on a boundary mesh with inserted points.
TEST(IntrinsicDelaunay, TracesAreOptional) {
  const MeshData bunny = read_mesh(iarap::test::data_path("bunny.off"));
  TestMesh grid = iarap::test::planar_grid(10, 0.3, 3);
  iarap::test::random_planar_flips(grid, 120, 11);
  const TestMesh strip = obtuse_strip();
  const std::pair<const char*, std::pair<Eigen::MatrixXd, Eigen::MatrixXi>> cases[] = {
      {"bunny", {bunny.V, bunny.F}},
      {"flipped grid", {grid.V, grid.F}},
      {"obtuse strip", {strip.V, strip.F}}};
  for (const auto& [name, mesh] : cases) {
    IntrinsicOptions options;
    options.refine_boundary = true;
    const IntrinsicDelaunay with = intrinsic_delaunay(mesh.first, mesh.second, options);
    options.keep_traces = false;
    const IntrinsicDelaunay without = intrinsic_delaunay(mesh.first, mesh.second, options);
    EXPECT_TRUE(without.traces.start.empty() && without.traces.a.empty()) << name;
    EXPECT_EQ(with.traces.start.size(), static_cast<size_t>(with.triangulation.E.rows()) + 1) << name;
    // Edges that are not input edges (flipped, or made by a boundary split) exist, so the compact path runs.
    if (name == std::string("obtuse strip"))
      EXPECT_GT(with.triangulation.inserted_t.size(), 0);
    else
      EXPECT_GT(with.triangulation.flips, 0) << name;
    EXPECT_EQ(without.segments.edge_start, with.segments.edge_start) << name;
    EXPECT_EQ(without.segments.face, with.segments.face) << name;
    EXPECT_EQ(without.segments.b_index, with.segments.b_index) << name;
    EXPECT_EQ(without.segments.b_value, with.segments.b_value) << name;
    EXPECT_EQ(without.segments.weight, with.segments.weight) << name;
    EXPECT_EQ(Eigen::MatrixXd(without.segments.B - with.segments.B).cwiseAbs().maxCoeff(), 0.0) << name;
  }
}

TEST(IntrinsicDelaunay, SharedSurfaceMeshes) {
  int tested = 0;
  for (const std::string name :
       {"planexy.off", "grid.off", "decimated-knight.off", "spike.ply", "halftunnel.off", "3holes.off",
        "fertility.off", "horse.obj", "cactus.obj", "elephant.obj", "cheburashka.off", "lion.off",
        "camelhead.off", "armadillo_30K.obj", "beetle.off", "face.obj", "ogre.obj"}) {
    const std::string path = iarap::test::shared_mesh_in_loop(name);
    if (path.empty()) continue;
    const MeshData mesh = read_mesh(path);
    const IntrinsicDelaunay idt = intrinsic_delaunay(mesh.V, mesh.F);
    expect_invariants(mesh.V, mesh.F, idt, name);
    ++tested;
  }
  if (tested == 0) GTEST_SKIP() << "shared meshes not found beside the repository";
}

TEST(IntrinsicDelaunay, FlatMeshMadeNonDelaunayReturnsToPlanarDelaunay) {
  TestMesh m = iarap::test::planar_grid(10, 0.3, 3);
  iarap::test::random_planar_flips(m, 120, 11);
  const IntrinsicDelaunay idt = intrinsic_delaunay(m.V, m.F);
  EXPECT_GT(idt.triangulation.non_delaunay_before, 10);
  expect_invariants(m.V, m.F, idt, "flipped grid");
  expect_planar_delaunay(m.V, idt, "flipped grid");
}

TEST(IntrinsicDelaunay, ZigzagStripCrossesManyEdges) {
  const TestMesh m = iarap::test::zigzag_strip(24);
  const IntrinsicDelaunay idt = intrinsic_delaunay(m.V, m.F);
  const int max_segments = expect_invariants(m.V, m.F, idt, "zigzag strip");
  EXPECT_GE(max_segments, 12);
  expect_planar_delaunay(m.V, idt, "zigzag strip");
}

TEST(IntrinsicDelaunay, HighValenceFan) {
  const TestMesh m = iarap::test::ellipse_fan(120);
  const IntrinsicDelaunay idt = intrinsic_delaunay(m.V, m.F);
  EXPECT_GT(idt.triangulation.flips, 50);
  expect_invariants(m.V, m.F, idt, "fan");
  expect_planar_delaunay(m.V, idt, "fan");
}

TEST(IntrinsicDelaunay, SharpConeApex) {
  const TestMesh m = iarap::test::closed_cone(7, 3, 12.0, 0.5);
  const IntrinsicDelaunay idt = intrinsic_delaunay(m.V, m.F);
  EXPECT_GT(idt.triangulation.flips, 0);
  expect_invariants(m.V, m.F, idt, "cone");
}

TEST(IntrinsicDelaunay, DeltaComplexWithDoubleEdges) {
  // A closed three-sided cone flips into a Delta-complex where two edges join the same pair of vertices;
  // weights and segments are indexed per edge, so both edges keep their own trace.
  const TestMesh m = iarap::test::closed_cone(3, 2, 2.0);
  const IntrinsicDelaunay idt = intrinsic_delaunay(m.V, m.F);
  const auto& E = idt.triangulation.E;
  std::set<std::pair<int, int>> pairs;
  int repeated = 0;
  for (int e = 0; e < E.rows(); ++e)
    if (!pairs.insert({std::min(E(e, 0), E(e, 1)), std::max(E(e, 0), E(e, 1))}).second) ++repeated;
  EXPECT_GT(repeated, 0);
  expect_invariants(m.V, m.F, idt, "three-sided cone");
}

TEST(IntrinsicDelaunay, EdgeCrossesTheSameInputEdgeTwice) {
  // Issue 4: an intrinsic edge winding round a sharp apex crosses one input edge twice. Its trace must still
  // be one consistent polyline: two distinct crossings and the intrinsic length.
  const TestMesh m = iarap::test::wrapped_pyramid();
  const IntrinsicDelaunay idt = intrinsic_delaunay(m.V, m.F);
  expect_invariants(m.V, m.F, idt, "wrapped pyramid");
  const auto& tri = idt.triangulation;
  const auto& tr = idt.traces;
  auto point = [&](int k) {
    return tr.c[k] < 0 ? Eigen::Vector3d(m.V.row(tr.a[k]))
                       : Eigen::Vector3d((1 - tr.t[k]) * m.V.row(tr.a[k]) + tr.t[k] * m.V.row(tr.c[k]));
  };
  int most = 0;
  std::string most_where = "none";
  for (int e = 0; e < tri.E.rows(); ++e) {
    // The interior trace points by the input edge {x, y} (x < y) they cross, as parameters from x to y.
    std::map<std::pair<int, int>, std::vector<double>> crossings;
    for (int k = tr.start[e] + 1; k + 1 < tr.start[e + 1]; ++k)
      crossings[std::minmax(tr.a[k], tr.c[k])].push_back(tr.a[k] < tr.c[k] ? tr.t[k] : 1 - tr.t[k]);
    for (const auto& [input_edge, t] : crossings) {
      std::string where = "edge " + std::to_string(e) + " (" + std::to_string(tri.E(e, 0)) + " -> " +
                          std::to_string(tri.E(e, 1)) + ") crossing input edge {" +
                          std::to_string(input_edge.first) + ", " + std::to_string(input_edge.second) + "}";
      where += " at t =";
      for (double ti : t) where += " " + std::to_string(ti);
      if (static_cast<int>(t.size()) > most) {
        most = static_cast<int>(t.size());
        most_where = where;
      }
      if (t.size() < 2) continue;
      for (size_t i = 0; i < t.size(); ++i) {
        EXPECT_GT(t[i], 0.0) << where;
        EXPECT_LT(t[i], 1.0) << where;
        for (size_t j = 0; j < i; ++j)
          EXPECT_GT(std::abs(t[i] - t[j]), 1e-6) << "two crossings coincide: " << where;
      }
      // Each piece of the trace is straight in its input face, so the polyline has the intrinsic length.
      double traced = 0.0;
      for (int k = tr.start[e]; k + 1 < tr.start[e + 1]; ++k) traced += (point(k + 1) - point(k)).norm();
      EXPECT_NEAR(traced, tri.length(e), 1e-9 * tri.length(e)) << where;
    }
  }
  EXPECT_GE(most, 2) << "no intrinsic edge crosses one input edge twice; the most crossings: " << most_where
                     << " (" << tri.flips << " flips)";
}

TEST(IntrinsicDelaunay, DegenerateTriangleIsMollifiedOrNamed) {
  // A flat square with vertex 4 on its bottom edge.
  Eigen::MatrixXd V(5, 3);
  V << 0, 0, 0, 2, 0, 0, 2, 2, 0, 0, 2, 0, 1, 0, 0;
  // Three proper faces plus the zero-area sliver (0, 1, 4) under the bottom edge.
  Eigen::MatrixXi Fz(4, 3);
  Fz << 0, 4, 3, 4, 1, 2, 4, 2, 3, 0, 1, 4;
  IntrinsicOptions strict;
  strict.mollify = false;
  try {
    intrinsic_delaunay(V, Fz, strict);
    ADD_FAILURE() << "expected a TopologyError for the zero-area face";
  } catch (const TopologyError& e) {
    EXPECT_NE(std::string(e.what()).find("face 3"), std::string::npos) << e.what();
  }
  const IntrinsicDelaunay idt = intrinsic_delaunay(V, Fz);
  EXPECT_GT(idt.triangulation.mollify_delta, 0.0);
  EXPECT_TRUE(idt.triangulation.cot_weight.allFinite());
  EXPECT_TRUE(idt.segments.weight.allFinite());
  EXPECT_TRUE(idt.segments.s_hat.allFinite());
}

TEST(IntrinsicDelaunay, NonManifoldInputIsNamed) {
  // Three faces on edge (0, 1).
  Eigen::MatrixXd V(5, 3);
  V << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, -1, 0, 0, 0, 1;
  Eigen::MatrixXi F(3, 3);
  F << 0, 1, 2, 1, 0, 3, 0, 1, 4;
  try {
    intrinsic_delaunay(V, F);
    ADD_FAILURE() << "expected a TopologyError";
  } catch (const TopologyError& e) {
    EXPECT_NE(std::string(e.what()).find("non-manifold edge (0, 1)"), std::string::npos) << e.what();
  }
}

TEST(IntrinsicDelaunay, VertexWithTwoClosedFansIsNamed) {
  // Two closed square pyramids touching at their tips (vertex 0): every edge is manifold and vertex 0 has
  // no boundary halfedge, but its halfedges form two closed fans (the interior sweep's early return to
  // its first halfedge).
  Eigen::MatrixXd V(9, 3);
  V << 0, 0, 0, 1, 0, 1, 0, 1, 1, -1, 0, 1, 0, -1, 1, 1, 0, -1, 0, 1, -1, -1, 0, -1, 0, -1, -1;
  Eigen::MatrixXi F(12, 3);
  F << 0, 2, 1, 0, 3, 2, 0, 4, 3, 0, 1, 4, 1, 2, 3, 1, 3, 4, 0, 5, 6, 0, 6, 7, 0, 7, 8, 0, 8, 5, 5, 7, 6, 5,
      8, 7;
  try {
    intrinsic_delaunay(V, F);
    ADD_FAILURE() << "expected a TopologyError";
  } catch (const TopologyError& e) {
    EXPECT_NE(std::string(e.what()).find("non-manifold vertex 0"), std::string::npos) << e.what();
  }
}

TEST(IntrinsicDelaunay, BoundaryRefinementRemovesObtuseBoundaryAngles) {
  const TestMesh m = obtuse_strip();
  IntrinsicOptions options;
  options.refine_boundary = true;
  const IntrinsicDelaunay paper = intrinsic_delaunay(m.V, m.F);
  const IntrinsicDelaunay idt = intrinsic_delaunay(m.V, m.F, options);
  EXPECT_GT(paper.triangulation.obtuse_boundary_before, 0);
  EXPECT_EQ(idt.triangulation.obtuse_boundary_after, 0);
  EXPECT_GT(idt.triangulation.inserted_t.size(), 0);
  for (int e = 0; e < idt.triangulation.E.rows(); ++e)
    EXPECT_GE(idt.triangulation.cot_weight(e), -1e-12) << "edge " << e;
  expect_invariants(m.V, m.F, idt, "refined strip");
  expect_planar_delaunay_edges_straight(m.V, idt, "refined strip");
}

TEST(IntrinsicDelaunay, BoundaryRefinementOnSharedMeshes) {
  int tested = 0;
  for (const std::string name :
       {"lion.off", "beetle.off", "ogre.obj", "face.obj", "camelhead.off", "spike.ply", "grid.off"}) {
    const std::string path = iarap::test::shared_mesh_in_loop(name);
    if (path.empty()) continue;
    const MeshData mesh = read_mesh(path);
    IntrinsicOptions options;
    options.refine_boundary = true;
    const IntrinsicDelaunay idt = intrinsic_delaunay(mesh.V, mesh.F, options);
    EXPECT_EQ(idt.triangulation.obtuse_boundary_after, 0) << name;
    EXPECT_GE(idt.triangulation.cot_weight.minCoeff(), -1e-12) << name;
    expect_invariants(mesh.V, mesh.F, idt, name + " refined");
    if (idt.triangulation.obtuse_boundary_before == 0) {
      EXPECT_EQ(idt.triangulation.inserted_t.size(), 0) << name;
    }
    ++tested;
  }
  if (tested == 0) GTEST_SKIP() << "shared meshes not found beside the repository";
}
