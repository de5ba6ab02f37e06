// Anderson acceleration of a fixed-point map x -> G(x) (Walker & Ni 2011; for geometry optimization Peng,
// Deng, Zhang et al. 2018). With residuals f_k = G(x_k) - x_k and the last m differences
// dF_j = f_{j+1} - f_j, dG_j = G(x_{j+1}) - G(x_j), the next iterate is G(x_k) - dG theta with theta the
// least-squares minimizer of ||f_k - dF theta||. Used by arap_solve over the free vertices' positions,
// where G is the local/global step; the caller owns the energy safeguard (reset() after a rejection).
#pragma once
#include <Eigen/Core>

namespace iarap::detail {

class AndersonAcceleration {
public:
  // window m >= 1 past differences; vectors of `size` entries.
  AndersonAcceleration(int window, Eigen::Index size);

  // Takes x_k and G(x_k) (size entries each) and writes the accelerated iterate to next. Returns false
  // (next = G(x_k)) while there is no history: the first call and the first after reset().
  bool step(const double* x, const double* Gx, double* next);

  // Forgets the history: the next step() returns G(x) itself.
  void reset();

private:
  int window_;
  Eigen::Index size_;
  int columns_ = 0; // differences held, <= window_
  int newest_ = -1; // column of the newest difference (circular)
  bool has_previous_ = false;
  Eigen::MatrixXd dF_, dG_; // size x window: differences, each pair scaled so that ||dF_j|| = 1
  Eigen::MatrixXd gram_;    // window x window: dF^T dF
  Eigen::VectorXd dF_f_;    // dF^T f_k, kept up to date from the Gram columns
  Eigen::VectorXd f_prev_, G_prev_, f_, df_;
};

} // namespace iarap::detail
