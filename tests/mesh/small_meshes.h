// Tiny meshes built in code for the validation, repair and subdivision tests.
#pragma once
#include "iarap/mesh/subdivide.h"

#include <Eigen/Core>
#include <cmath>

namespace iarap::test {

struct SmallMesh {
  Eigen::MatrixXd V;
  Eigen::MatrixXi F;
};

// Regular octahedron, closed, genus 0, outward-oriented; bbox diagonal 2 * sqrt(3).
inline SmallMesh octahedron() {
  SmallMesh m;
  m.V.resize(6, 3);
  m.V << 1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1;
  m.F.resize(8, 3);
  m.F << 0, 2, 4, 2, 1, 4, 1, 3, 4, 3, 0, 4, 2, 0, 5, 1, 2, 5, 3, 1, 5, 0, 3, 5;
  return m;
}

// The octahedron subdivided once (midpoints): 18 vertices, 32 faces, closed, outward-oriented, Delaunay.
inline SmallMesh subdivided_octahedron() {
  SmallMesh m = octahedron();
  subdivide_midpoint(m.V, m.F, 1);
  return m;
}

// Two closed square pyramids (apex up and apex down) that touch only at vertex 0: a non-manifold vertex
// whose faces form two fans, while every edge is manifold.
inline SmallMesh two_cones_sharing_a_tip() {
  SmallMesh m;
  m.V.resize(9, 3);
  m.V << 0, 0, 0,                               // shared tip
      1, 0, 1, 0, 1, 1, -1, 0, 1, 0, -1, 1,     // upper base ring (z = 1)
      1, 0, -1, 0, 1, -1, -1, 0, -1, 0, -1, -1; // lower base ring (z = -1)
  m.F.resize(12, 3);
  // Upper cone: sides (tip, b_{i+1}, b_i) facing outward (down/out), base (1,2,3),(1,3,4) facing up.
  m.F << 0, 2, 1, 0, 3, 2, 0, 4, 3, 0, 1, 4, 1, 2, 3, 1, 3, 4,
      // Lower cone: mirrored orientation.
      0, 5, 6, 0, 6, 7, 0, 7, 8, 0, 8, 5, 5, 7, 6, 5, 8, 7;
  return m;
}

// m with the rows of V appended to its vertices and those of F (on the vertices of both) to its faces.
inline SmallMesh appended(const SmallMesh& m, const Eigen::MatrixXd& V, const Eigen::MatrixXi& F) {
  SmallMesh out;
  out.V.resize(m.V.rows() + V.rows(), 3);
  out.V << m.V, V;
  out.F.resize(m.F.rows() + F.rows(), 3);
  out.F << m.F, F;
  return out;
}

// The mesh as an STL-like triangle soup: every face gets its own three copies of its corners.
inline SmallMesh as_soup(const SmallMesh& mesh) {
  SmallMesh s;
  s.V.resize(3 * mesh.F.rows(), 3);
  s.F.resize(mesh.F.rows(), 3);
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      s.V.row(3 * f + k) = mesh.V.row(mesh.F(f, k));
      s.F(f, k) = static_cast<int>(3 * f + k);
    }
  return s;
}

} // namespace iarap::test

namespace iarap::test {

// A Moebius strip of n quads (2 n triangles) around a circle of radius 2, width 1: manifold, one boundary
// loop, no consistent orientation.
inline SmallMesh moebius_strip(int n = 12) {
  SmallMesh m;
  m.V.resize(2 * n, 3);
  for (int i = 0; i < n; ++i) {
    const double t = 2 * 3.14159265358979323846 * i / n, half = t / 2;
    for (int side = 0; side < 2; ++side) {
      const double s = side == 0 ? -0.5 : 0.5;
      m.V.row(2 * i + side) << (2 + s * std::cos(half)) * std::cos(t), (2 + s * std::cos(half)) * std::sin(t),
          s * std::sin(half);
    }
  }
  m.F.resize(2 * n, 3);
  for (int i = 0; i < n; ++i) {
    const int a = 2 * i, b = 2 * i + 1;
    // The last quad joins the first with its sides swapped: the half twist.
    const int c = i + 1 < n ? 2 * (i + 1) : 1, d = i + 1 < n ? 2 * (i + 1) + 1 : 0;
    m.F.row(2 * i) << a, c, b;
    m.F.row(2 * i + 1) << b, c, d;
  }
  return m;
}

} // namespace iarap::test
