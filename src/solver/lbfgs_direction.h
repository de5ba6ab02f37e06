// The L-BFGS search direction d = -H g (Nocedal & Wright, Algorithm 7.4, the two-loop recursion) with the
// initial inverse Hessian H_0 = L_ff^{-1}: the factorized global-step matrix, as in Liu, Bouaziz and Kavan
// 2017 ("Quasi-Newton methods for real-time simulation of hyperelastic materials"). With no history the
// direction is -L_ff^{-1} g, i.e. exactly the plain local/global step, so L-BFGS only adds curvature that
// the fixed L misses (the rotations' response to the positions).
#pragma once
#include <Eigen/Core>

#include <vector>

namespace iarap::detail {

class LbfgsDirection {
public:
  explicit LbfgsDirection(int window);

  // Stores the pair s = x_next - x, y = g_next - g unless its curvature s^T y is not clearly positive
  // (the energy is not convex; such a pair would make H indefinite). Returns whether it was kept. One pass
  // over the four inputs writes s and y and sums s^T y, |s|^2 and |y|^2 (this runs every iteration).
  bool push(const Eigen::MatrixXd& x_next, const Eigen::MatrixXd& x, const Eigen::MatrixXd& g_next,
            const Eigen::MatrixXd& g);

  // d = -H g, with H_0 r = H0(r) (arap_solve: the back-substitution with the factor of L_ff).
  template <class InitialInverseHessian>
  Eigen::MatrixXd direction(const Eigen::MatrixXd& g, const InitialInverseHessian& H0) const {
    Eigen::MatrixXd q = g;
    std::vector<double> alpha(static_cast<size_t>(pairs_));
    newest_to_oldest(q, alpha);
    Eigen::MatrixXd r = H0(q);
    oldest_to_newest(alpha, r);
    return r;
  }

  void reset() { pairs_ = 0; }
  int pairs() const { return pairs_; }

private:
  // The two loops of the recursion: q -= alpha_a y_a (newest first), then r += (alpha_a - beta_a) s_a and
  // r = -r (oldest first).
  void newest_to_oldest(Eigen::MatrixXd& q, std::vector<double>& alpha) const;
  void oldest_to_newest(const std::vector<double>& alpha, Eigen::MatrixXd& r) const;

  int window_;
  int pairs_ = 0;   // held, <= window_
  int newest_ = -1; // slot of the newest pair (circular)
  std::vector<Eigen::MatrixXd> s_, y_;
  Eigen::MatrixXd spare_s_, spare_y_; // the candidate pair; swapped into the ring when kept
  std::vector<double> rho_;           // 1 / (s^T y)
};

} // namespace iarap::detail
