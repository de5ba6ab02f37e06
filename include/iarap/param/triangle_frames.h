// Each triangle of a surface laid flat, isometrically, in a 2D frame of its own, as the linear operator
// that takes a UV map to the triangle's 2x2 Jacobian.
//
// Triangle f = (i, j, k) gets the frame x_i = (0, 0), x_j = (|e_ij|, 0), x_k with a positive second
// coordinate, so a map keeping the face's orientation has det J_f > 0. With U_f the 3 x 2 UV rows of
// (i, j, k), J_f = U_f^T D_f, D_f = [-1 -1; 1 0; 0 1] [x_j - x_i, x_k - x_i]^-1 (3 x 2): row c of D_f is
// the gradient of the hat function of corner c. sum_f area_f D_f D_f^T (scattered) is the cotan Laplacian.
#pragma once
#include <Eigen/Core>

namespace iarap {

struct TriangleFrames {
  Eigen::VectorXd area; // #F area of each triangle, squared mesh units
  Eigen::MatrixXd D;    // #F x 6 D_f row by row: (D(c,0), D(c,1)) of corner c in columns 2c, 2c+1
};

// Frames of the triangles of (V #V x 3, F #F x 3). Assumes valid indices; a zero-area face gives
// non-finite entries in D (prepare_disk refuses such faces first).
TriangleFrames triangle_frames(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F);

// J_f of face f under UV (#V x 2).
Eigen::Matrix2d face_jacobian(const TriangleFrames& frames, const Eigen::MatrixXi& F,
                              const Eigen::MatrixXd& UV, Eigen::Index f);

// #F x 4: J_f row by row (J(0,0), J(0,1), J(1,0), J(1,1)) for every face.
Eigen::MatrixXd face_jacobians(const TriangleFrames& frames, const Eigen::MatrixXi& F,
                               const Eigen::MatrixXd& UV);
// The same into J, resized only when its shape differs (an iteration reuses one buffer).
void face_jacobians(const TriangleFrames& frames, const Eigen::MatrixXi& F, const Eigen::MatrixXd& UV,
                    Eigen::MatrixXd& J);

} // namespace iarap
