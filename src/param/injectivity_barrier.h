// The term that keeps a flip-free UV iteration injective: per face area_f mu psi(det J_f) with
// psi(x) = -log(x / eps) + x / eps - 1 below eps (zero, with zero slope, at eps and above) and +infinity at
// x <= 0, and the step bound that goes with it: the line search never tries a map past the first
// degenerate triangle (injective_step.h) times step_fraction. A barrier alone is not enough (a trial past
// a fold has infinite energy and is halved away, but the halving can take many trials), and a bound alone
// is not either: the global step keeps pointing into the same nearly degenerate triangles and the steps
// shrink geometrically (measured on camelhead: t = 6e-7 after 9 iterations, stopped at E = 1.06 against
// 0.80). Faces already folded in the start map (a Tutte map degenerate in floating point) are left to the
// elastic energy: no barrier, no bound. Internal to the param module.
#pragma once
#include "iarap/param/disk_mesh.h"

#include <Eigen/Core>
#include <vector>

namespace iarap::param_detail {

class InjectivityBarrier {
public:
  // weight mu > 0, threshold eps > 0, step_fraction in (0, 1); J0 (#F x 4): the start map's Jacobians.
  InjectivityBarrier(const DiskMesh& disk, double weight, double threshold, double step_fraction,
                     const Eigen::MatrixXd& J0);

  // sum_f area_f mu psi(det J_f) for J #F x 4 (row by row); +infinity when a face folded.
  double value(const Eigen::MatrixXd& J) const;
  // grad (#V x 2) += d value / dU at the map whose Jacobians are J.
  void add_gradient(const Eigen::MatrixXd& J, Eigen::MatrixXd& grad) const;
  // out (#V x 2) += the Hessian of value at J applied to the direction whose face Jacobians are dJ.
  void add_hessian_product(const Eigen::MatrixXd& J, const Eigen::MatrixXd& dJ, Eigen::MatrixXd& out) const;
  // step_fraction * the first t > 0 at which some face of J + t dJ degenerates; +infinity if none does.
  double step_limit(const Eigen::MatrixXd& J, const Eigen::MatrixXd& dJ) const;

private:
  const DiskMesh& disk_;
  double weight_, threshold_, step_fraction_;
  std::vector<unsigned char> exempt_; // #F: folded in the start map
  mutable Eigen::MatrixXd A_;         // #F x 4 per-face matrices to scatter
};

} // namespace iarap::param_detail
