// The drag's motion: where a method's last two answers moved the free vertices, so that the next update of
// the drag starts where that motion leads instead of at the last answer.
//
// An update stops at its time budget, short of the minimum of its targets: the answers lag. Started from
// the last answer U_k, the next update must first cover the targets' new step and the lag left; the lag
// grows until the few iterations of an update remove as much as one step adds (the beetle's drag, plain
// updates: a last answer 1.7e-2 above its minimum in energy). Moving the free vertices on by the answers'
// last step, U_k + s (U_k - U_{k-1}), first covers the step that the targets repeat: on a steady drag the
// answers' step is the minimizers' step, so the update starts with the lag of the answer before and its
// iterations go into reducing it. s measures how much of the targets' last step the new targets repeat,
// s = <T - T_k, T_k - T_{k-1}> / |T_k - T_{k-1}|^2 clamped to [0, 2]: 0 when the handle holds still or turns
// back (no prediction), 1 on a steady drag. The prediction is a starting point only: every update then
// iterates, and a descent method from any start lowers the energy.
#pragma once
#include <Eigen/Core>

namespace iarap::serve {

class DragMotion {
public:
  // Forget the motion (new constraints, a new mesh, a reset, a solve that asked for no prediction).
  void clear();
  // The scale s of the next update with hard targets `targets` (#constrained x 3); 0 without two answers of
  // targets of this size before, or with a targets' step of zero length.
  double scale(const Eigen::MatrixXd& targets) const;
  // U += s (U_k - U_{k-1}) at every row: the constrained rows are set to their targets by the solve.
  void extrapolate(double s, Eigen::MatrixXd& U) const;
  // After an update answered U for `targets`: its step from the answer before (of the same size) is kept.
  void record(const Eigen::MatrixXd& U, const Eigen::MatrixXd& targets);

private:
  Eigen::MatrixXd answer_, targets_;          // U_k and T_k (0 x 0: no answer yet)
  Eigen::MatrixXd answer_step_, target_step_; // U_k - U_{k-1}, T_k - T_{k-1} (0 x 0: one answer only)
};

} // namespace iarap::serve
