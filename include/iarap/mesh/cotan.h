// Cotangents of triangle angles and the cotan Laplacian of the extrinsic mesh.
//
// Sign convention used throughout iarap: Laplacians are positive semi-definite,
// L(i,j) = -w_ij for i != j and L(i,i) = sum_j w_ij, with w_ij = (cot a_ij + cot b_ij) / 2.
// "Positive weights" therefore means non-positive off-diagonal entries.
#pragma once
#include <Eigen/Core>
#include <Eigen/SparseCore>

namespace iarap {

// #F x 3 cotangent of the angle at corner k of face f, computed from the three edge lengths
// (so it serves intrinsic lengths too). A zero-area face gives +-infinity or NaN; callers check.
Eigen::MatrixXd face_cotangents(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F);

// Cotangent of the angle opposite side a in a triangle with side lengths a, b, c (Heron-free,
// stable formula through the squared lengths and 4 * area).
double cotangent_from_lengths(double a, double b, double c);

// Area of a triangle from its side lengths, by the numerically stable Kahan form of Heron's formula.
double triangle_area_from_lengths(double a, double b, double c);

// #V x #V cotan Laplacian of (V, F) in the sign convention above.
Eigen::SparseMatrix<double> cotan_laplacian(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F);

} // namespace iarap
