#include "quadratic_terms.h"

namespace iarap::detail {

namespace {
int row_of(const std::vector<int>* position, int v) {
  return position ? (*position)[static_cast<size_t>(v)] : v;
}
} // namespace

SoftPointTerm::SoftPointTerm(const ArapData& data, const Eigen::MatrixXd& targets,
                             const std::vector<int>* position)
    : points_(soft_points(data.soft, data.F)), targets_(targets), position_(position),
      weighted_(static_cast<size_t>(data.soft.soft_size())) {}

// s = sum_k 2 W_k c_k t_k^T (the hard points' too: they are in Q).
void SoftPointTerm::add_linear(const std::vector<int>& unknown, Eigen::MatrixXd& s) const {
  for (size_t k = 0; k < points_.size(); ++k) {
    const SoftPoint& p = points_[k];
    for (int j = 0; j < 3; ++j) {
      const int row = unknown[static_cast<size_t>(p.v[j])];
      if (row >= 0) s.row(row) += 2.0 * p.W * p.c[j] * targets_.row(static_cast<Eigen::Index>(k));
    }
  }
}

double SoftPointTerm::energy(const ArapElements::ValueRows& U) const {
  return soft_penalty(points_, targets_, U.data(), position_, weighted_);
}

ForceTerm::ForceTerm(const Eigen::MatrixXd& forces, const Eigen::MatrixXd& V,
                     const std::vector<int>* position)
    : forces_(forces.rows(), 3), position_(position), f_dot_rest_(forces.cwiseProduct(V).sum()) {
  for (Eigen::Index v = 0; v < forces.rows(); ++v)
    forces_.row(row_of(position, static_cast<int>(v))) = forces.row(v);
}

// s = f: the energy -f . (U - V) has gradient -f.
void ForceTerm::add_linear(const std::vector<int>& unknown, Eigen::MatrixXd& s) const {
  for (size_t v = 0; v < unknown.size(); ++v)
    if (unknown[v] >= 0) s.row(unknown[v]) += forces_.row(row_of(position_, static_cast<int>(v)));
}

double ForceTerm::energy(const ArapElements::ValueRows& U) const {
  return f_dot_rest_ - forces_.cwiseProduct(U).sum();
}

std::vector<std::unique_ptr<QuadraticTerm>> quadratic_terms(const ArapData& data,
                                                            const Eigen::MatrixXd& soft_targets,
                                                            const Eigen::MatrixXd& forces,
                                                            const std::vector<int>* position) {
  std::vector<std::unique_ptr<QuadraticTerm>> terms;
  if (data.soft.size() > 0) terms.push_back(std::make_unique<SoftPointTerm>(data, soft_targets, position));
  if (forces.rows() > 0) terms.push_back(std::make_unique<ForceTerm>(forces, data.V, position));
  return terms;
}

} // namespace iarap::detail
