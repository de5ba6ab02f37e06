// iarap's rotation smoothing against CGAL 5.5's SRE_ARAP (docs/smoothing.md): the same scene solved by
// CGAL's Surface_mesh_deformation<..., SRE_ARAP> with unclamped cotangent weights, run to a fixed point, and
// by arap_solve (original ARAP, ArapSolveOptions::rotation_smoothing = alpha, Newton to 1e-14); prints the
// largest vertex distance between the two as a fraction of the bounding-box diagonal, and the range of the
// mesh's valences (CGAL's per-vertex rule and the symmetric energy agree when they are all equal).
//
//   iarap_cgal_sre_compare [mesh.off ...]     (no argument: the valence-6 torus only)
//
// The scene: a ring (torus) or the bottom 10% along y (other meshes) fixed at rest, the opposite ring or
// the top 10% lifted by 0.2 of the diagonal and turned 30 degrees about x. Built only with
// -DIARAP_BUILD_CGAL_COMPARISON=ON (CGAL is GPL; this program is never installed).
#include "iarap/io/read_mesh.h"
#include "iarap/solver/arap.h"

#include <CGAL/Simple_cartesian.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Surface_mesh_deformation.h>

#include <Eigen/Geometry>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

namespace {

using Kernel = CGAL::Simple_cartesian<double>;
using Point = Kernel::Point_3;
using Mesh = CGAL::Surface_mesh<Point>;
using Halfedge = boost::graph_traits<Mesh>::halfedge_descriptor;

// (cot a + cot b) / 2 of the angles opposite the half-edge's edge, one term on a boundary edge: CGAL's
// Cotangent_weight without its clamp of each cotangent at zero (issue 45 compares unclamped energies).
struct UnclampedCotangentWeight {
  template <class PointMap> double operator()(Halfedge he, const Mesh& mesh, PointMap points) const {
    const auto cot_opposite = [&](Halfedge h) {
      if (CGAL::is_border(h, mesh)) return 0.0;
      const auto a = get(points, source(h, mesh)), b = get(points, target(h, mesh)),
                 c = get(points, target(next(h, mesh), mesh));
      const Eigen::Vector3d u(a.x() - c.x(), a.y() - c.y(), a.z() - c.z()),
          v(b.x() - c.x(), b.y() - c.y(), b.z() - c.z());
      return u.dot(v) / u.cross(v).norm();
    };
    return 0.5 * (cot_opposite(he) + cot_opposite(opposite(he, mesh)));
  }
};

using Deformation = CGAL::Surface_mesh_deformation<Mesh, CGAL::Default, CGAL::Default, CGAL::SRE_ARAP,
                                                   UnclampedCotangentWeight>;

// A torus (radii 1 and 0.4) on an n x m grid, every quad split along the same diagonal: valence 6.
void torus(int n, int m, Eigen::MatrixXd& V, Eigen::MatrixXi& F) {
  V.resize(n * m, 3);
  F.resize(2 * n * m, 3);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < m; ++j) {
      const double u = 2 * M_PI * i / n, v = 2 * M_PI * j / m;
      V.row(i * m + j) << (1 + 0.4 * std::cos(v)) * std::cos(u), (1 + 0.4 * std::cos(v)) * std::sin(u),
          0.4 * std::sin(v);
      const int a = i * m + j, b = ((i + 1) % n) * m + j, c = ((i + 1) % n) * m + (j + 1) % m,
                d = i * m + (j + 1) % m;
      F.row(2 * (i * m + j)) << a, b, c;
      F.row(2 * (i * m + j) + 1) << a, c, d;
    }
}

struct Scene {
  std::string name;
  Eigen::MatrixXd V;
  Eigen::MatrixXi F;
  std::vector<int> fixed, handle;
};

Scene torus_scene() {
  Scene s{"torus 48 x 16 (valence 6)", {}, {}, {}, {}};
  torus(48, 16, s.V, s.F);
  for (int j = 0; j < 16; ++j) {
    s.fixed.push_back(j);            // ring u = 0
    s.handle.push_back(24 * 16 + j); // ring u = pi
  }
  return s;
}

Scene file_scene(const std::string& path) {
  const iarap::MeshData mesh = iarap::read_mesh(path);
  Scene s{path, mesh.V, mesh.F, {}, {}};
  const double low = s.V.col(1).minCoeff(), high = s.V.col(1).maxCoeff();
  for (int v = 0; v < s.V.rows(); ++v) {
    if (s.V(v, 1) <= low + 0.1 * (high - low)) s.fixed.push_back(v);
    if (s.V(v, 1) >= high - 0.1 * (high - low)) s.handle.push_back(v);
  }
  return s;
}

double diagonal(const Eigen::MatrixXd& V) {
  return (V.colwise().maxCoeff() - V.colwise().minCoeff()).norm();
}

// The handle's targets: lifted along z by 0.2 of the diagonal, turned 30 degrees about x through its centre.
Eigen::MatrixXd handle_targets(const Scene& s) {
  Eigen::MatrixXd T(static_cast<Eigen::Index>(s.handle.size()), 3);
  Eigen::RowVector3d centre = Eigen::RowVector3d::Zero();
  for (const int v : s.handle) centre += s.V.row(v);
  centre /= static_cast<double>(s.handle.size());
  const Eigen::Matrix3d turn = Eigen::AngleAxisd(M_PI / 6, Eigen::Vector3d::UnitX()).toRotationMatrix();
  for (size_t k = 0; k < s.handle.size(); ++k)
    T.row(static_cast<Eigen::Index>(k)) = (s.V.row(s.handle[k]) - centre) * turn.transpose() + centre +
                                          Eigen::RowVector3d(0, 0, 0.2 * diagonal(s.V));
  return T;
}

// CGAL's SRE_ARAP from the rest shape, in chunks of 500 iterations until no vertex moves more than 1e-13 of
// the diagonal in a chunk (or 200000 iterations). Returns the positions; prints the iterations it took.
Eigen::MatrixXd cgal_solve(const Scene& s, double alpha) {
  Mesh mesh;
  std::vector<Mesh::Vertex_index> vertex;
  for (Eigen::Index v = 0; v < s.V.rows(); ++v)
    vertex.push_back(mesh.add_vertex(Point(s.V(v, 0), s.V(v, 1), s.V(v, 2))));
  for (Eigen::Index f = 0; f < s.F.rows(); ++f)
    if (mesh.add_face(vertex[s.F(f, 0)], vertex[s.F(f, 1)], vertex[s.F(f, 2)]) == Mesh::null_face())
      std::fprintf(stderr, "%s: CGAL refused face %ld\n", s.name.c_str(), static_cast<long>(f));
  Deformation deformation(mesh);
  deformation.set_sre_arap_alpha(alpha);
  deformation.insert_roi_vertices(vertices(mesh).begin(), vertices(mesh).end());
  for (const int v : s.fixed) deformation.insert_control_vertex(vertex[static_cast<size_t>(v)]);
  for (const int v : s.handle) deformation.insert_control_vertex(vertex[static_cast<size_t>(v)]);
  const Eigen::MatrixXd T = handle_targets(s);
  for (size_t k = 0; k < s.handle.size(); ++k)
    deformation.set_target_position(vertex[static_cast<size_t>(s.handle[k])],
                                    Point(T(static_cast<Eigen::Index>(k), 0),
                                          T(static_cast<Eigen::Index>(k), 1),
                                          T(static_cast<Eigen::Index>(k), 2)));
  const auto positions = [&] {
    Eigen::MatrixXd U(s.V.rows(), 3);
    for (Eigen::Index v = 0; v < s.V.rows(); ++v) {
      const Point& p = mesh.point(vertex[static_cast<size_t>(v)]);
      U.row(v) << p.x(), p.y(), p.z();
    }
    return U;
  };
  Eigen::MatrixXd U = positions();
  int iterations = 0;
  double moved = 0.0;
  do {
    deformation.deform(500, 0.0);
    iterations += 500;
    const Eigen::MatrixXd next = positions();
    moved = (next - U).rowwise().norm().maxCoeff() / diagonal(s.V);
    U = next;
  } while (moved > 1e-13 && iterations < 200000);
  std::printf("  CGAL: %d iterations, last 500 moved %.2e of the diagonal\n", iterations, moved);
  return U;
}

// From `start` (the rest shape, or CGAL's result: then the minimizer of the symmetric energy nearest to
// CGAL's fixed point, whatever other minima the energy has).
Eigen::MatrixXd iarap_solve(const Scene& s, double alpha, const Eigen::MatrixXd& start) {
  std::vector<int> all = s.fixed;
  all.insert(all.end(), s.handle.begin(), s.handle.end());
  const Eigen::VectorXi fixed =
      Eigen::Map<const Eigen::VectorXi>(all.data(), static_cast<Eigen::Index>(all.size()));
  Eigen::MatrixXd targets(fixed.size(), 3);
  for (size_t k = 0; k < s.fixed.size(); ++k) targets.row(static_cast<Eigen::Index>(k)) = s.V.row(s.fixed[k]);
  targets.bottomRows(static_cast<Eigen::Index>(s.handle.size())) = handle_targets(s);
  iarap::ArapOptions options;
  options.method = iarap::ArapMethod::Arap;
  iarap::ArapData data = iarap::arap_precompute(s.V, s.F, fixed, options);
  Eigen::MatrixXd U = start;
  iarap::ArapSolveOptions solve;
  solve.accelerator = iarap::ArapAccelerator::Newton;
  solve.max_iterations = 500;
  solve.tolerance = 1e-14;
  solve.rotation_smoothing = alpha;
  const iarap::ArapReport report = iarap::arap_solve(data, targets, U, solve);
  std::printf("  iarap: %d Newton iterations (%s), energy %.12g\n", report.iterations,
              iarap::arap_stop_reason_name(report.stop_reason).c_str(), report.energies.back());
  return U;
}

} // namespace

int main(int argc, char** argv) {
  std::vector<Scene> scenes{torus_scene()};
  for (int k = 1; k < argc; ++k) scenes.push_back(file_scene(argv[k]));
  for (const Scene& s : scenes)
    for (const double alpha : {0.0, 0.02, 0.2}) { // 0: the control, original ARAP on both sides
      Eigen::VectorXi valence = Eigen::VectorXi::Zero(s.V.rows()); // one-ring size: edges counted once
      for (Eigen::Index f = 0; f < s.F.rows(); ++f)
        for (int k = 0; k < 3; ++k) ++valence(s.F(f, k)); // faces around a vertex = valence when closed
      std::printf("%s, %ld vertices, faces per vertex %d to %d, alpha %g\n", s.name.c_str(),
                  static_cast<long>(s.V.rows()), valence.minCoeff(), valence.maxCoeff(), alpha);
      const Eigen::MatrixXd U_cgal = cgal_solve(s, alpha);
      for (const bool from_cgal : {false, true}) {
        const Eigen::MatrixXd U_iarap = iarap_solve(s, alpha, from_cgal ? U_cgal : s.V);
        std::printf("  from %s: largest distance %.3e of the diagonal (mean %.3e)\n",
                    from_cgal ? "CGAL's result" : "the rest shape",
                    (U_cgal - U_iarap).rowwise().norm().maxCoeff() / diagonal(s.V),
                    (U_cgal - U_iarap).rowwise().norm().mean() / diagonal(s.V));
      }
    }
  return 0;
}
