#include "iarap/param/triangle_frames.h"

#include <Eigen/Dense>

namespace iarap {

TriangleFrames triangle_frames(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F) {
  TriangleFrames frames;
  frames.area.resize(F.rows());
  frames.D.resize(F.rows(), 6);
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    const Eigen::Vector3d p0 = V.row(F(f, 0)), e1 = V.row(F(f, 1)).transpose() - p0,
                          e2 = V.row(F(f, 2)).transpose() - p0;
    // Frame: x_j = (|e1|, 0), x_k = (e2 . e1 / |e1|, |e1 x e2| / |e1|).
    const double l1 = e1.norm(), cross = e1.cross(e2).norm();
    Eigen::Matrix2d X;
    X << l1, e2.dot(e1) / l1, 0, cross / l1;
    frames.area(f) = 0.5 * cross;
    Eigen::Matrix<double, 3, 2> corners;
    corners << -1, -1, 1, 0, 0, 1;
    // D = corners X^-1 with X upper triangular: X^-1 = [1/l1, -X01/(l1 X11); 0, 1/X11].
    Eigen::Matrix2d X_inverse;
    X_inverse << 1 / X(0, 0), -X(0, 1) / (X(0, 0) * X(1, 1)), 0, 1 / X(1, 1);
    const Eigen::Matrix<double, 3, 2> D = corners * X_inverse;
    for (int c = 0; c < 3; ++c) {
      frames.D(f, 2 * c) = D(c, 0);
      frames.D(f, 2 * c + 1) = D(c, 1);
    }
  }
  return frames;
}

Eigen::Matrix2d face_jacobian(const TriangleFrames& frames, const Eigen::MatrixXi& F,
                              const Eigen::MatrixXd& UV, Eigen::Index f) {
  Eigen::Matrix2d J = Eigen::Matrix2d::Zero();
  for (int c = 0; c < 3; ++c) {
    const Eigen::Index v = F(f, c);
    const double dx = frames.D(f, 2 * c), dy = frames.D(f, 2 * c + 1);
    J(0, 0) += UV(v, 0) * dx;
    J(0, 1) += UV(v, 0) * dy;
    J(1, 0) += UV(v, 1) * dx;
    J(1, 1) += UV(v, 1) * dy;
  }
  return J;
}

Eigen::MatrixXd face_jacobians(const TriangleFrames& frames, const Eigen::MatrixXi& F,
                               const Eigen::MatrixXd& UV) {
  Eigen::MatrixXd J;
  face_jacobians(frames, F, UV, J);
  return J;
}

void face_jacobians(const TriangleFrames& frames, const Eigen::MatrixXi& F, const Eigen::MatrixXd& UV,
                    Eigen::MatrixXd& J) {
  J.resize(F.rows(), 4);
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    const Eigen::Matrix2d Jf = face_jacobian(frames, F, UV, f);
    J.row(f) << Jf(0, 0), Jf(0, 1), Jf(1, 0), Jf(1, 1);
  }
}

} // namespace iarap
