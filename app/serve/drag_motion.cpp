#include "drag_motion.h"

#include <algorithm>

namespace iarap::serve {

void DragMotion::clear() {
  answer_.resize(0, 0);
  targets_.resize(0, 0);
  answer_step_.resize(0, 0);
  target_step_.resize(0, 0);
}

double DragMotion::scale(const Eigen::MatrixXd& targets) const {
  if (target_step_.size() == 0 || targets.rows() != targets_.rows() || targets.cols() != targets_.cols())
    return 0;
  const double length2 = target_step_.squaredNorm();
  if (!(length2 > 0)) return 0;
  const double repeated = ((targets - targets_).array() * target_step_.array()).sum() / length2;
  return std::clamp(repeated, 0.0, 2.0); // also 0 for a NaN (non-finite targets are refused before)
}

void DragMotion::extrapolate(double s, Eigen::MatrixXd& U) const {
  if (s > 0 && answer_step_.rows() == U.rows() && answer_step_.cols() == U.cols()) U += s * answer_step_;
}

void DragMotion::record(const Eigen::MatrixXd& U, const Eigen::MatrixXd& targets) {
  if (answer_.rows() == U.rows() && answer_.cols() == U.cols() && targets_.rows() == targets.rows() &&
      targets_.cols() == targets.cols()) {
    answer_step_ = U - answer_; // same sizes: no allocation after the first steps
    target_step_ = targets - targets_;
  } else {
    answer_step_.resize(0, 0);
    target_step_.resize(0, 0);
  }
  answer_ = U;
  targets_ = targets;
}

} // namespace iarap::serve
