#include "hard_points.h"

#include <cmath>

namespace iarap::detail {

namespace {

// The entry of row a times row b (C C^T): the columns they share.
double row_dot(const ConstraintRow& a, const ConstraintRow& b) {
  double s = 0.0;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      if (a.column[i] >= 0 && a.column[i] == b.column[j]) s += a.c[i] * b.c[j];
  return s;
}

} // namespace

HardPointProjection::HardPointProjection(std::vector<ConstraintRow> rows, Eigen::Index n,
                                         const std::function<Eigen::MatrixXd(const Eigen::MatrixXd&)>& solve)
    : rows_(std::move(rows)) {
  // Greedy independent subset by an incremental Cholesky factor G_II = K K^T of the Gram matrix: a row
  // whose residual against the kept ones is below 1e-12 of its own square norm is their combination.
  const auto m = static_cast<Eigen::Index>(rows_.size());
  Eigen::MatrixXd K = Eigen::MatrixXd::Zero(m, m);
  for (Eigen::Index k = 0; k < m; ++k) {
    const ConstraintRow& row = rows_[static_cast<size_t>(k)];
    const auto kept = static_cast<Eigen::Index>(independent_.size());
    Eigen::VectorXd g(kept);
    for (Eigen::Index i = 0; i < kept; ++i) g(i) = row_dot(rows_[static_cast<size_t>(independent_[i])], row);
    const Eigen::VectorXd l =
        kept > 0 ? Eigen::VectorXd(K.topLeftCorner(kept, kept).triangularView<Eigen::Lower>().solve(g))
                 : Eigen::VectorXd();
    const double norm2 = row_dot(row, row);
    const double residual = norm2 - l.squaredNorm();
    if (norm2 > 0 && residual > 1e-12 * norm2) {
      K.row(kept).head(kept) = l.transpose();
      K(kept, kept) = std::sqrt(residual);
      independent_.push_back(k);
    } else {
      const Eigen::VectorXd alpha =
          kept > 0 ? Eigen::VectorXd(
                         K.topLeftCorner(kept, kept).triangularView<Eigen::Lower>().transpose().solve(l))
                   : Eigen::VectorXd();
      dependent_.emplace_back(k, alpha);
    }
  }
  if (independent_.empty()) return;
  const auto kept = static_cast<Eigen::Index>(independent_.size());
  Eigen::MatrixXd Ct = Eigen::MatrixXd::Zero(n, kept); // C_I^T, dense: one solve for all its columns
  for (Eigen::Index i = 0; i < kept; ++i) {
    const ConstraintRow& row = rows_[static_cast<size_t>(independent_[static_cast<size_t>(i)])];
    for (int j = 0; j < 3; ++j)
      if (row.column[j] >= 0) Ct(row.column[j], i) += row.c[j];
  }
  Y_ = solve(Ct);
  S_.emplace(independent_times(Y_));
}

Eigen::MatrixXd HardPointProjection::independent_times(const Eigen::MatrixXd& x) const {
  Eigen::MatrixXd Cx = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(independent_.size()), x.cols());
  for (size_t i = 0; i < independent_.size(); ++i) {
    const ConstraintRow& row = rows_[static_cast<size_t>(independent_[i])];
    for (int j = 0; j < 3; ++j)
      if (row.column[j] >= 0) Cx.row(static_cast<Eigen::Index>(i)) += row.c[j] * x.row(row.column[j]);
  }
  return Cx;
}

void HardPointProjection::correct(Eigen::MatrixXd& x, const Eigen::MatrixXd& d) const {
  if (independent_.empty()) return;
  Eigen::MatrixXd r = independent_times(x);
  for (size_t i = 0; i < independent_.size(); ++i)
    r.row(static_cast<Eigen::Index>(i)) -= d.row(independent_[i]);
  x.noalias() -= Y_ * S_->solve(r);
}

void HardPointProjection::project(Eigen::MatrixXd& x) const {
  if (independent_.empty()) return;
  x.noalias() -= Y_ * S_->solve(independent_times(x));
}

void HardPointProjection::project_gradient(Eigen::MatrixXd& g) const {
  if (independent_.empty()) return;
  const Eigen::MatrixXd mu = S_->solve(Y_.transpose() * g); // |I| x 3
  for (size_t i = 0; i < independent_.size(); ++i) {
    const ConstraintRow& row = rows_[static_cast<size_t>(independent_[i])];
    for (int j = 0; j < 3; ++j)
      if (row.column[j] >= 0) g.row(row.column[j]) -= row.c[j] * mu.row(static_cast<Eigen::Index>(i));
  }
}

std::optional<ConstraintConflict> HardPointProjection::find_conflict(const Eigen::MatrixXd& d,
                                                                     double tol) const {
  for (const auto& [k, alpha] : dependent_) {
    Eigen::RowVector3d predicted = Eigen::RowVector3d::Zero();
    Eigen::Index largest = -1;
    for (Eigen::Index i = 0; i < alpha.size(); ++i) {
      predicted += alpha(i) * d.row(independent_[static_cast<size_t>(i)]);
      if (std::abs(alpha(i)) > 1e-12 && (largest < 0 || std::abs(alpha(i)) > std::abs(alpha(largest))))
        largest = i;
    }
    const double gap = (d.row(k) - predicted).norm();
    if (gap > tol)
      return ConstraintConflict{k, largest < 0 ? -1 : independent_[static_cast<size_t>(largest)], gap};
  }
  return std::nullopt;
}

} // namespace iarap::detail
