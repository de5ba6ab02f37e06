// How far a UV map is from an isometry, per triangle and in summary: the per-triangle ARAP energy, det J,
// singular values and the flipped triangles.
#pragma once
#include "iarap/param/triangle_frames.h"

#include <Eigen/Core>

namespace iarap {

struct DistortionRange {
  double min = 0, median = 0, max = 0;
};

struct MapDistortion {
  // sum_f area_f ||J_f - R_f||_F^2, R_f = closest_rotation_2d(J_f) (Liu et al. 2008 without the 1/2).
  double energy = 0;
  // The same energy of s * UV at the s > 0 minimizing it, and that s: comparable between maps of any
  // scale (a fixed circular boundary, another tool's output).
  double scaled_energy = 0, best_scale = 1;
  int flipped = 0;             // triangles with det J_f <= 0
  double min_det_J = 0;        // min_f det J_f = UV area / surface area of the face (signed)
  DistortionRange area_ratio;  // sigma1 * sigma2 over the faces (1 for an area-preserving map)
  DistortionRange angle_ratio; // sigma1 / sigma2 (1 for a conformal map; +infinity where sigma2 = 0)
};

// Distortion of UV (#V x 2) over the triangles of `frames` and F (#F x 3).
MapDistortion map_distortion(const TriangleFrames& frames, const Eigen::MatrixXi& F,
                             const Eigen::MatrixXd& UV);

// Singular values (sigma1 >= sigma2 >= 0) of a 2x2 matrix in closed form.
Eigen::Vector2d singular_values_2d(const Eigen::Matrix2d& J);

} // namespace iarap
