// Disk-like (and deliberately not disk-like) meshes built in code for the param tests.
#pragma once
#include "intrinsic/mesh_generators.h"

#include <Eigen/Core>

#include <cmath>
#include <functional>

namespace iarap::test {

// planar_grid(n)'s faces over (s, t) in [0, 1]^2, vertices placed by position(s, t): counter-clockwise
// in (s, t).
inline TestMesh grid_sheet(int n, const std::function<Eigen::Vector3d(double, double)>& position) {
  TestMesh mesh = planar_grid(n);
  for (Eigen::Index v = 0; v < mesh.V.rows(); ++v) mesh.V.row(v) = position(mesh.V(v, 0), mesh.V(v, 1));
  return mesh;
}

// The unit square [0, 1]^2 at z = 0.
inline TestMesh flat_square(int n) {
  return planar_grid(n);
}

// A quarter of a cylinder of radius 1 and height 1, rolled up from a 0.5 pi x 1 sheet: developable.
inline TestMesh quarter_cylinder(int n) {
  return grid_sheet(n, [](double s, double t) {
    const double angle = 0.5 * M_PI * s;
    return Eigen::Vector3d(std::cos(angle), std::sin(angle), t);
  });
}

// Polar rings around a centre: `rings` rings of `sectors` vertices each between radius inner and 1, and
// with inner == 0 a centre vertex joined to the first ring (a disk), else a hole (an annulus). Vertices
// placed by position(r, angle); faces counter-clockwise in the plane.
inline TestMesh polar_mesh(int rings, int sectors, double inner,
                           const std::function<Eigen::Vector3d(double, double)>& position) {
  const bool disk = inner == 0;
  const int first = disk ? 1 : 0; // index of ring 0's first vertex
  TestMesh mesh;
  const int ring_count = disk ? rings : rings + 1;
  mesh.V.resize(first + ring_count * sectors, 3);
  if (disk) mesh.V.row(0) = position(0, 0);
  for (int r = 0; r < ring_count; ++r)
    for (int k = 0; k < sectors; ++k) {
      const double radius = disk ? double(r + 1) / rings : inner + (1 - inner) * r / rings;
      const double angle = 2 * M_PI * (k + 0.5 * (r % 2)) / sectors;
      mesh.V.row(first + r * sectors + k) = position(radius, angle);
    }
  const int fans = disk ? sectors : 0;
  mesh.F.resize(fans + 2 * sectors * (ring_count - 1), 3);
  int f = 0;
  if (disk)
    for (int k = 0; k < sectors; ++k) mesh.F.row(f++) << 0, 1 + k, 1 + (k + 1) % sectors;
  for (int r = 0; r + 1 < ring_count; ++r)
    for (int k = 0; k < sectors; ++k) {
      const int a = first + r * sectors + k, b = first + r * sectors + (k + 1) % sectors;
      const int c = first + (r + 1) * sectors + k, d = first + (r + 1) * sectors + (k + 1) % sectors;
      mesh.F.row(f++) << a, c, d;
      mesh.F.row(f++) << a, d, b;
    }
  return mesh;
}

// A flat disk of radius 1 at z = 0.
inline TestMesh flat_disk(int rings, int sectors) {
  return polar_mesh(rings, sectors, 0,
                    [](double r, double a) { return Eigen::Vector3d(r * std::cos(a), r * std::sin(a), 0); });
}

// The cap of the unit sphere within `polar_angle` of the north pole.
inline TestMesh spherical_cap(int rings, int sectors, double polar_angle) {
  return polar_mesh(rings, sectors, 0, [polar_angle](double r, double a) {
    const double theta = polar_angle * r;
    return Eigen::Vector3d(std::sin(theta) * std::cos(a), std::sin(theta) * std::sin(a), std::cos(theta));
  });
}

// A flat annulus between radius 0.4 and 1: two boundary loops.
inline TestMesh flat_annulus(int rings, int sectors) {
  return polar_mesh(rings, sectors, 0.4,
                    [](double r, double a) { return Eigen::Vector3d(r * std::cos(a), r * std::sin(a), 0); });
}

// A closed torus of radii 2 and 1, n x m quads each split in two; outward-oriented.
inline TestMesh torus(int n, int m) {
  TestMesh mesh;
  mesh.V.resize(n * m, 3);
  for (int j = 0; j < m; ++j)
    for (int i = 0; i < n; ++i) {
      const double u = 2 * M_PI * i / n, v = 2 * M_PI * j / m;
      mesh.V.row(j * n + i) << (2 + std::cos(v)) * std::cos(u), (2 + std::cos(v)) * std::sin(u), std::sin(v);
    }
  mesh.F.resize(2 * n * m, 3);
  int f = 0;
  for (int j = 0; j < m; ++j)
    for (int i = 0; i < n; ++i) {
      const int a = j * n + i, b = j * n + (i + 1) % n, c = ((j + 1) % m) * n + i,
                d = ((j + 1) % m) * n + (i + 1) % n;
      mesh.F.row(f++) << a, b, d;
      mesh.F.row(f++) << a, d, c;
    }
  return mesh;
}

} // namespace iarap::test
