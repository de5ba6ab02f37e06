// Small meshes built in code for the intrinsic-triangulation tests: flat grids (Delaunay or made
// non-Delaunay by flips), a zigzag strip, a high-valence fan, cones and a pyramid with a wrapping edge.
#pragma once
#include <Eigen/Core>

#include <cmath>
#include <map>
#include <random>
#include <utility>
#include <vector>

namespace iarap::test {

struct TestMesh {
  Eigen::MatrixXd V;
  Eigen::MatrixXi F;
};

// n x n squares in [0,1]^2 (z = 0), each split by the same diagonal, vertices jittered in-plane by
// jitter * spacing. jitter = 0 gives a Delaunay mesh (right triangles: opposite angles sum to pi).
inline TestMesh planar_grid(int n, double jitter = 0.0, unsigned seed = 1) {
  TestMesh m;
  m.V.resize((n + 1) * (n + 1), 3);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const double h = 1.0 / n;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      const bool border = i == 0 || j == 0 || i == n || j == n;
      const double dx = border ? 0.0 : jitter * h * u(rng), dy = border ? 0.0 : jitter * h * u(rng);
      m.V.row(j * (n + 1) + i) << i * h + dx, j * h + dy, 0.0;
    }
  m.F.resize(2 * n * n, 3);
  int f = 0;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const int a = j * (n + 1) + i, b = a + 1, c = a + n + 1, d = c + 1;
      m.F.row(f++) << a, b, d;
      m.F.row(f++) << a, d, c;
    }
  return m;
}

// Flips random interior edges of a planar mesh whose quad is strictly convex, so the result is still a
// valid planar triangulation of the same points, usually far from Delaunay.
inline void random_planar_flips(TestMesh& m, int flips, unsigned seed = 7) {
  std::mt19937 rng(seed);
  auto cross2 = [&](int o, int a, int b) {
    const Eigen::Vector3d p = m.V.row(o), q = m.V.row(a), r = m.V.row(b);
    return (q.x() - p.x()) * (r.y() - p.y()) - (q.y() - p.y()) * (r.x() - p.x());
  };
  for (int attempt = 0, done = 0; done < flips && attempt < 50 * flips; ++attempt) {
    std::map<std::pair<int, int>, std::pair<int, int>> edge_faces; // directed edge -> (face, corner opposite)
    for (int f = 0; f < m.F.rows(); ++f)
      for (int k = 0; k < 3; ++k) edge_faces[{m.F(f, k), m.F(f, (k + 1) % 3)}] = {f, (k + 2) % 3};
    std::uniform_int_distribution<int> pick(0, static_cast<int>(m.F.rows()) - 1), corner(0, 2);
    const int f0 = pick(rng), k = corner(rng);
    const int a = m.F(f0, k), b = m.F(f0, (k + 1) % 3), c = m.F(f0, (k + 2) % 3);
    auto it = edge_faces.find({b, a});
    if (it == edge_faces.end()) continue;
    const int f1 = it->second.first, d = m.F(f1, it->second.second);
    // Convex quad a, d, b, c (counter-clockwise): the new diagonal c-d must separate a from b.
    if (cross2(c, d, a) * cross2(c, d, b) >= 0 || cross2(a, b, c) * cross2(a, b, d) >= 0) continue;
    if (std::abs(cross2(c, a, d)) < 1e-3 / m.V.rows() || std::abs(cross2(d, b, c)) < 1e-3 / m.V.rows())
      continue;
    m.F.row(f0) << c, a, d;
    m.F.row(f1) << d, b, c;
    ++done;
  }
}

// A thin strip of n cells: bottom row B_i = (i, 0), top row T_i = (i, h). Triangulated as a fan from T_0
// to every B_i and a fan from B_n to every T_i, so the Delaunay (vertical-ish) edges cross many input edges.
inline TestMesh zigzag_strip(int n, double h = 0.3) {
  TestMesh m;
  m.V.resize(2 * (n + 1), 3);
  for (int i = 0; i <= n; ++i) {
    m.V.row(i) << i, 0, 0;               // B_i
    m.V.row(n + 1 + i) << i + 0.5, h, 0; // T_i (shifted so no four points are cocircular)
  }
  std::vector<Eigen::Vector3i> faces;
  const int t0 = n + 1, bn = n;
  for (int i = 0; i < n; ++i) faces.emplace_back(t0, i, i + 1);           // fan from T_0
  for (int i = 0; i < n; ++i) faces.emplace_back(bn, t0 + i + 1, t0 + i); // fan from B_n
  m.F.resize(static_cast<int>(faces.size()), 3);
  for (size_t f = 0; f < faces.size(); ++f) m.F.row(static_cast<int>(f)) = faces[f].transpose();
  return m;
}

// A flat fan: one centre vertex joined to `valence` vertices on an off-centre ellipse (a valence-100+
// vertex whose spokes are mostly non-Delaunay).
inline TestMesh ellipse_fan(int valence, double a = 1.0, double b = 0.15, double centre_x = 0.85) {
  TestMesh m;
  m.V.resize(valence + 1, 3);
  m.V.row(0) << centre_x, 0, 0;
  for (int k = 0; k < valence; ++k) {
    const double t = 2 * M_PI * k / valence;
    m.V.row(k + 1) << a * std::cos(t), b * std::sin(t), 0;
  }
  m.F.resize(valence, 3);
  for (int k = 0; k < valence; ++k) m.F.row(k) << 0, k + 1, (k + 1) % valence + 1;
  return m;
}

// A closed cone: apex at height `height`, `sides` base vertices on the unit circle in `rings` rings
// between base and apex, and a base centre. A tall cone has an apex of small angle sum.
inline TestMesh closed_cone(int sides, int rings, double height, double twist = 0.0) {
  TestMesh m;
  const int nv = sides * rings + 2;
  m.V.resize(nv, 3);
  for (int r = 0; r < rings; ++r) {
    const double s = 1.0 - static_cast<double>(r) / rings;
    for (int k = 0; k < sides; ++k) {
      const double t = 2 * M_PI * (k + twist * r) / sides;
      m.V.row(r * sides + k) << s * std::cos(t), s * std::sin(t), height * (1.0 - s);
    }
  }
  const int apex = sides * rings, centre = apex + 1;
  m.V.row(apex) << 0, 0, height;
  m.V.row(centre) << 0, 0, 0;
  std::vector<Eigen::Vector3i> faces;
  for (int r = 0; r + 1 < rings; ++r)
    for (int k = 0; k < sides; ++k) {
      const int a = r * sides + k, b = r * sides + (k + 1) % sides;
      const int c = (r + 1) * sides + k, d = (r + 1) * sides + (k + 1) % sides;
      faces.emplace_back(a, b, d);
      faces.emplace_back(a, d, c);
    }
  for (int k = 0; k < sides; ++k) {
    const int top = (rings - 1) * sides;
    faces.emplace_back(top + k, top + (k + 1) % sides, apex);
    faces.emplace_back(centre, (k + 1) % sides, k);
  }
  m.F.resize(static_cast<int>(faces.size()), 3);
  for (size_t f = 0; f < faces.size(); ++f) m.F.row(static_cast<int>(f)) = faces[f].transpose();
  return m;
}

// A strip of cols x rows cells whose rows are sheared by half a cell, so the boundary triangles along the
// long sides are obtuse (negative boundary cotan weights that flips cannot remove). bend_radius > 0 bends
// it over a cylinder of that radius (x becomes an arc), 0 keeps it flat.
inline TestMesh sheared_strip(int cols, int rows, double bend_radius = 0.0) {
  TestMesh m;
  m.V.resize((rows + 1) * (cols + 1), 3);
  for (int r = 0; r <= rows; ++r)
    for (int c = 0; c <= cols; ++c) {
      const double x = c + 0.5 * (r % 2), y = 0.25 * r;
      if (bend_radius > 0)
        m.V.row(r * (cols + 1) + c) << bend_radius * std::sin(x / bend_radius), y,
            bend_radius * std::cos(x / bend_radius);
      else
        m.V.row(r * (cols + 1) + c) << x, y, 0.0;
    }
  m.F.resize(2 * rows * cols, 3);
  int f = 0;
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < cols; ++c) {
      const int a = r * (cols + 1) + c, b = a + 1, d = a + cols + 1, e = d + 1;
      if (r % 2 == 0) {
        m.F.row(f++) << a, b, d;
        m.F.row(f++) << b, e, d;
      } else {
        m.F.row(f++) << a, e, d;
        m.F.row(f++) << a, b, e;
      }
    }
  return m;
}

// An open three-sided pyramid with a sharp apex. Every vertex but the apex lies on a panel or a ridge, so the
// lateral surface is intrinsically a flat cone of angle 0.76 (about 0.24 pi). In the middle panel the input
// edge x2 -> y leaves base vertex x2 nearly parallel to the panel's other ridge; p lies on one side of it and
// q on the other, further out. Besides a short p-q edge crossing x2 -> y once, the intrinsic Delaunay
// triangulation has a second p-q edge that goes the long way round the apex (sweeping 0.725 of the cone
// angle 0.76, across all three ridges) and so crosses x2 -> y twice: just after leaving p and again before
// reaching q (issue 4). The double crossing survives random changes of all lengths and angles by 5%.
// Vertices: 0 apex, 1-3 base x0..x2 and 4-6 far points on the three ridges, 7 y, 8 p, 9 q.
inline TestMesh wrapped_pyramid() {
  const double panel[3] = {0.17, 0.33, 0.26}; // apex angle of each panel (ridge i to ridge i + 1)
  const double base[3] = {0.7, 0.75, 0.85}, far = 5.0;
  // Unit ridge directions, consecutive ones at the panel angles (a spherical triangle).
  Eigen::Vector3d ridge[3];
  ridge[0] << 1, 0, 0;
  ridge[1] << std::cos(panel[0]), std::sin(panel[0]), 0;
  const double y2 = (std::cos(panel[1]) - std::cos(panel[0]) * std::cos(panel[2])) / std::sin(panel[0]);
  ridge[2] << std::cos(panel[2]), y2, std::sqrt(1 - std::cos(panel[2]) * std::cos(panel[2]) - y2 * y2);
  // The point of the middle panel at `angle` from ridge 1 and distance r from the apex.
  const Eigen::Vector3d u = ridge[1], v = (ridge[2] - ridge[1].dot(ridge[2]) * ridge[1]).normalized();
  auto middle_panel = [&](double angle, double r) {
    return Eigen::Vector3d(r * (std::cos(angle) * u + std::sin(angle) * v));
  };
  TestMesh m;
  m.V.resize(10, 3);
  m.V.row(0).setZero();
  for (int i = 0; i < 3; ++i) {
    m.V.row(1 + i) = base[i] * ridge[i];
    m.V.row(4 + i) = far * ridge[i];
  }
  m.V.row(7) = middle_panel(panel[1] - 0.27, 3.5);  // y
  m.V.row(8) = middle_panel(panel[1] - 0.15, 1.13); // p
  m.V.row(9) = middle_panel(panel[1] - 0.185, 2.6); // q
  m.F.resize(15, 3);
  m.F << 0, 1, 2, 0, 2, 3, 0, 3, 1,                                           // the apex's star
      1, 4, 5, 1, 5, 2,                                                       // panel 0
      2, 8, 3, 3, 8, 7, 3, 7, 9, 3, 9, 6, 9, 7, 6, 6, 7, 5, 2, 5, 7, 2, 7, 8, // middle panel; 3-7 is x2 -> y
      3, 6, 4, 3, 4, 1;                                                       // panel 2
  return m;
}

} // namespace iarap::test
