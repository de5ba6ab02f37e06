// What a registration fits to: a triangle mesh or a point cloud, with a unit normal per point (given, the
// mesh's area-weighted vertex normals, or estimated by PCA) and the k-d tree of its points.
#pragma once
#include "iarap/registration/closest_surface_point.h"
#include "iarap/registration/point_index.h"

#include <Eigen/Core>

#include <string>

namespace iarap {

struct RegistrationTarget {
  Eigen::MatrixXd points;  // #P x 3
  Eigen::MatrixXd normals; // #P x 3 unit normals
  Eigen::MatrixXi faces;   // #TF x 3 over points, or 0 x 3 for a point cloud
  bool oriented = true;    // false: normals estimated by PCA, compared up to sign
  double diagonal = 0;     // the bounding-box diagonal of points (distances are reported as fractions of it)
  PointIndex index;        // over points
  VertexFaces around;      // faces around each point (empty lists for a point cloud)
};

// Builds a target from arrays. points #P x 3, finite; normals #P x 3 or 0 x 0 (then the mesh's
// area-weighted vertex normals with faces, PCA of `normal_neighbours` nearest points without); faces #TF x 3
// or 0 x 0. Throws InputError naming `source` and the row for: no point, a non-finite coordinate or normal,
// a zero normal, a face index out of range, too few points to estimate normals (fewer than 3), and a
// target whose points all coincide.
RegistrationTarget make_registration_target(Eigen::MatrixXd points, Eigen::MatrixXd normals,
                                            Eigen::MatrixXi faces, const std::string& source,
                                            int normal_neighbours = 12);

// Reads a target file: a mesh (read_mesh: .obj .off .ply .stl; a vertex-only PLY or an OBJ with only v
// lines is a point cloud), or a .xyz point cloud ('x y z' or 'x y z nx ny nz' per line, '#' comments; all
// lines with the same count). Throws InputError naming "path:line" for bad tokens, and what
// make_registration_target throws, naming the path.
RegistrationTarget read_registration_target(const std::string& path, int normal_neighbours = 12);

} // namespace iarap
