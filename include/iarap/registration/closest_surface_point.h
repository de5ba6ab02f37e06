// The closest point of a triangle mesh to a query point, searched over the faces around a given vertex (the
// nearest vertex found by a PointIndex): registration's refinement from "nearest vertex" to "nearest point
// on the surface".
#pragma once
#include <Eigen/Core>

#include <vector>

namespace iarap {

// The faces around each vertex, flat (CSR): faces[offsets[v] .. offsets[v + 1]) are those using vertex v.
struct VertexFaces {
  std::vector<int> offsets; // #V + 1
  std::vector<int> faces;
};

// F #F x 3 with indices in [0, num_vertices) (not checked: the caller validated them).
VertexFaces vertex_faces(const Eigen::MatrixXi& F, Eigen::Index num_vertices);

struct SurfacePoint {
  int face = -1;                                         // the row of F, or -1 (a vertex on no face)
  Eigen::Vector3d barycentric = Eigen::Vector3d::Zero(); // over F.row(face), summing to 1
  Eigen::Vector3d position = Eigen::Vector3d::Zero();    // sum_k barycentric(k) V(F(face, k))
  double squared_distance = 0;                           // |position - query|^2
};

// The point of triangle (a, b, c) closest to p (Ericson, Real-Time Collision Detection, 5.1.5); its
// barycentric coordinates go to `barycentric`. Degenerate triangles give a point on their hull.
Eigen::Vector3d closest_point_on_triangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                                          const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                                          Eigen::Vector3d& barycentric);

// The point closest to p over the faces around `vertex` (vertex_faces(F)); for a vertex on no face, the
// vertex itself (face -1, barycentric zero).
SurfacePoint closest_point_near_vertex(const Eigen::Vector3d& p, const Eigen::MatrixXd& V,
                                       const Eigen::MatrixXi& F, const VertexFaces& around, int vertex);

} // namespace iarap
