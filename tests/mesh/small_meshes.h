// Tiny meshes built in code for the validation, repair and subdivision tests.
#pragma once
#include "iarap/mesh/subdivide.h"

#include <Eigen/Core>
#include <cmath>
#include <utility>

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

// The unit cube [0, 1]^3 as 12 outward-oriented triangles; vertex x + 2 y + 4 z is at (x, y, z).
inline SmallMesh unit_cube() {
  SmallMesh m;
  m.V.resize(8, 3);
  for (int v = 0; v < 8; ++v) m.V.row(v) << (v & 1), ((v >> 1) & 1), ((v >> 2) & 1);
  m.F.resize(12, 3);
  m.F << 0, 2, 1, 1, 2, 3, 4, 5, 6, 5, 7, 6, 0, 1, 5, 0, 5, 4, 2, 6, 7, 2, 7, 3, 0, 4, 6, 0, 6, 2, 1, 3, 7, 1,
      7, 5;
  return m;
}

// Two closed cubes touching at one corner, vertex 0 at the origin: the second is the first mirrored through
// it (faces reversed, so both are outward-oriented). Every edge is manifold; vertex 0 joins two closed fans.
inline SmallMesh two_cubes_at_a_corner() {
  const SmallMesh cube = unit_cube();
  Eigen::MatrixXd V2 = -cube.V.bottomRows(7);
  Eigen::MatrixXi F2(12, 3);
  for (int f = 0; f < 12; ++f)
    for (int k = 0; k < 3; ++k) {
      const int v = cube.F(f, k == 0 ? 0 : 3 - k); // reversed
      F2(f, k) = v == 0 ? 0 : v + 7;
    }
  return appended(cube, V2, F2);
}

// `faces` triangles standing on the edge (0, 1) from (0, 0, 0) to (1, 0, 0), fanned around it at unequal
// angles, every second one the other way round: an edge of `faces` faces and mixed orientation.
inline SmallMesh fin(int faces) {
  SmallMesh m;
  m.V.resize(faces + 2, 3);
  m.V.row(0) << 0, 0, 0;
  m.V.row(1) << 1, 0, 0;
  m.F.resize(faces, 3);
  for (int i = 0; i < faces; ++i) {
    const double angle = 2 * 3.14159265358979323846 * i / faces + 0.1 * i;
    m.V.row(i + 2) << 0.5 + 0.1 * i, std::cos(angle), std::sin(angle);
    if (i % 2 == 0)
      m.F.row(i) << 0, 1, i + 2;
    else
      m.F.row(i) << 1, 0, i + 2;
  }
  return m;
}

// A Klein bottle: the figure-8 immersion (self-intersecting in R^3) sampled on an n x m grid, the grid's
// last column glued to its first with v -> -v. Closed, no boundary, non-orientable; vertex i m + j at
// u = 2 pi i / n, v = 2 pi (j + 1/2) / m (the half step keeps the two sheets' crossing off the vertices).
inline SmallMesh klein_bottle(int n = 24, int m = 12) {
  const double pi = 3.14159265358979323846, r = 2.0;
  SmallMesh k;
  k.V.resize(n * m, 3);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < m; ++j) {
      const double u = 2 * pi * i / n, v = 2 * pi * (j + 0.5) / m;
      const double a = r + std::cos(u / 2) * std::sin(v) - std::sin(u / 2) * std::sin(2 * v);
      k.V.row(i * m + j) << a * std::cos(u), a * std::sin(u),
          std::sin(u / 2) * std::sin(v) + std::cos(u / 2) * std::sin(2 * v);
    }
  const auto vertex = [&](int i, int j) {
    if (i == n) return (m - 1 - ((j % m) + m) % m) % m; // u + 2 pi at v is u at -v
    return i * m + ((j % m) + m) % m;
  };
  k.F.resize(2 * n * m, 3);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < m; ++j) {
      const int a = vertex(i, j), b = vertex(i + 1, j), c = vertex(i + 1, j + 1), d = vertex(i, j + 1);
      k.F.row(2 * (i * m + j)) << a, b, c;
      k.F.row(2 * (i * m + j) + 1) << a, c, d;
    }
  return k;
}

// The mesh with every `every`-th face reversed (from face 0): orientable, inconsistently oriented.
inline SmallMesh with_mixed_orientation(SmallMesh m, int every) {
  for (Eigen::Index f = 0; f < m.F.rows(); f += every) std::swap(m.F(f, 1), m.F(f, 2));
  return m;
}

} // namespace iarap::test
