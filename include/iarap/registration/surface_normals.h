// Unit normals of registration's surfaces: area-weighted vertex normals of a triangle mesh, and normals of a
// point cloud estimated by PCA of each point's k nearest neighbours (the direction of least variance).
#pragma once
#include "iarap/registration/point_index.h"

#include <Eigen/Core>

#include <string>

namespace iarap {

// #V x 3: the sum of the (area-weighted, unnormalized) normals (b - a) x (c - a) of the faces around each
// vertex, normalized; a zero row for a vertex on no face of non-zero area. V #V x 3, F #F x 3 (indices not
// checked: the caller validated them).
Eigen::MatrixXd area_weighted_vertex_normals(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F);

// #P x 3 unit normals of the points P (#P x 3, indexed by `index`, built over the same P), each the
// eigenvector of the smallest eigenvalue of the covariance of its min(k, #P) nearest points (itself
// included). PCA gives no sign: each normal is turned away from the centroid of P (consistent on closed,
// star-shaped clouds; registration compares such normals up to sign). Throws InputError naming `source`
// when #P < 3 or k < 3 ("need at least 3 points to estimate normals").
Eigen::MatrixXd estimate_point_normals(const Eigen::MatrixXd& P, const PointIndex& index, int k,
                                       const std::string& source);

} // namespace iarap
