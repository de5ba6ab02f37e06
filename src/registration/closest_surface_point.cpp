#include "iarap/registration/closest_surface_point.h"

namespace iarap {

VertexFaces vertex_faces(const Eigen::MatrixXi& F, Eigen::Index num_vertices) {
  VertexFaces around;
  around.offsets.assign(static_cast<std::size_t>(num_vertices) + 1, 0);
  for (Eigen::Index f = 0; f < F.rows(); ++f)
    for (int k = 0; k < 3; ++k) ++around.offsets[static_cast<std::size_t>(F(f, k)) + 1];
  for (std::size_t v = 0; v + 1 < around.offsets.size(); ++v) around.offsets[v + 1] += around.offsets[v];
  around.faces.resize(static_cast<std::size_t>(around.offsets.back()));
  std::vector<int> next(around.offsets.begin(), around.offsets.end() - 1);
  for (Eigen::Index f = 0; f < F.rows(); ++f)
    for (int k = 0; k < 3; ++k)
      around.faces[static_cast<std::size_t>(next[static_cast<std::size_t>(F(f, k))]++)] = static_cast<int>(f);
  return around;
}

Eigen::Vector3d closest_point_on_triangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                                          const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                                          Eigen::Vector3d& barycentric) {
  const Eigen::Vector3d ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) {
    barycentric = {1, 0, 0};
    return a;
  }
  const Eigen::Vector3d bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) {
    barycentric = {0, 1, 0};
    return b;
  }
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) {
    const double v = d1 / (d1 - d3);
    barycentric = {1 - v, v, 0};
    return a + v * ab;
  }
  const Eigen::Vector3d cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) {
    barycentric = {0, 0, 1};
    return c;
  }
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) {
    const double w = d2 / (d2 - d6);
    barycentric = {1 - w, 0, w};
    return a + w * ac;
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
    const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    barycentric = {0, 1 - w, w};
    return b + w * (c - b);
  }
  const double sum = va + vb + vc;
  if (!(sum > 0)) { // degenerate: the nearest corner
    const double da = ap.squaredNorm(), db = bp.squaredNorm(), dc = cp.squaredNorm();
    barycentric = da <= db && da <= dc ? Eigen::Vector3d(1, 0, 0)
                  : db <= dc           ? Eigen::Vector3d(0, 1, 0)
                                       : Eigen::Vector3d(0, 0, 1);
    return barycentric(0) * a + barycentric(1) * b + barycentric(2) * c;
  }
  const double v = vb / sum, w = vc / sum;
  barycentric = {1 - v - w, v, w};
  return a + v * ab + w * ac;
}

SurfacePoint closest_point_near_vertex(const Eigen::Vector3d& p, const Eigen::MatrixXd& V,
                                       const Eigen::MatrixXi& F, const VertexFaces& around, int vertex) {
  SurfacePoint best;
  best.position = V.row(vertex).transpose();
  best.squared_distance = (best.position - p).squaredNorm();
  const auto v = static_cast<std::size_t>(vertex);
  for (int k = around.offsets[v]; k < around.offsets[v + 1]; ++k) {
    const int f = around.faces[static_cast<std::size_t>(k)];
    Eigen::Vector3d barycentric;
    const Eigen::Vector3d x = closest_point_on_triangle(
        p, V.row(F(f, 0)).transpose(), V.row(F(f, 1)).transpose(), V.row(F(f, 2)).transpose(), barycentric);
    const double squared = (x - p).squaredNorm();
    if (best.face < 0 || squared < best.squared_distance) {
      best = {f, barycentric, x, squared};
    }
  }
  return best;
}

} // namespace iarap
