// The terms of the total energy beside the elastic cells, as LocalGlobalProblem sums them (issue 43): the
// soft points (soft vertices and points on faces, arap_soft_constraints.h; the inertia of a simulation is
// such a soft vertex per free vertex, dynamics/simulation.h) and the linear external forces. Each has a
// constant Hessian Q_t (x) I_3 inside L's pattern, so that
//
//   E_t(U) = tr(U^T Q_t U) / 2 - tr(s_t^T U) + c_t,   grad E_t = Q_t U - s_t,   H_t v = Q_t v:
//
// Q_t is part of the factorized system matrix L + Q (ArapData::Q; none for forces), and the problem folds
// Q_t U and Q_t v into its fused passes over the rows of L + Q. A term gives the rest: its linear part s_t
// at the unknowns and its energy at the iterate. A new quadratic energy (registration's data terms, a
// stiffness-weighted pull) is one more subclass and one line in quadratic_terms(). Internal to the solver.
#pragma once
#include "iarap/solver/arap_types.h"

#include "soft_terms.h"

#include <Eigen/Core>

#include <memory>
#include <vector>

namespace iarap::detail {

class QuadraticTerm {
public:
  // The report field its energy goes to: ArapReport::penalty or ArapReport::potential.
  enum class Kind { Penalty, Potential };

  virtual ~QuadraticTerm() = default;
  virtual Kind kind() const = 0;
  // Adds s_t's rows of the unknowns to s (#unknowns x 3): vertex v's row is unknown[v] (-1: constrained,
  // skipped).
  virtual void add_linear(const std::vector<int>& unknown, Eigen::MatrixXd& s) const = 0;
  // E_t at positions U (row-major) in the order the term was made for.
  virtual double energy(const ArapElements::ValueRows& U) const = 0;
};

// sum_k W_k ||c_k^T U - t_k||^2 over data.soft's weighted points (the penalty P of arap_soft_constraints.h).
// The hard points share Q and s with internal weight kHardPointWeight (their energy is 0 on the constraint
// and is not counted).
class SoftPointTerm final : public QuadraticTerm {
public:
  // targets: #points x 3 (ArapSoftConstraints::size rows). position: row of each vertex in U (nullptr: the
  // file's order); it must outlive the term.
  SoftPointTerm(const ArapData& data, const Eigen::MatrixXd& targets, const std::vector<int>* position);
  Kind kind() const override { return Kind::Penalty; }
  void add_linear(const std::vector<int>& unknown, Eigen::MatrixXd& s) const override;
  double energy(const ArapElements::ValueRows& U) const override;

private:
  std::vector<SoftPoint> points_;
  Eigen::MatrixXd targets_;
  const std::vector<int>* position_;
  size_t weighted_; // the soft points come first, then the hard ones
};

// -f . (U - V) for constant forces f (#V x 3).
class ForceTerm final : public QuadraticTerm {
public:
  // f and the rest positions V in the file's order; position as for SoftPointTerm.
  ForceTerm(const Eigen::MatrixXd& forces, const Eigen::MatrixXd& V, const std::vector<int>* position);
  Kind kind() const override { return Kind::Potential; }
  void add_linear(const std::vector<int>& unknown, Eigen::MatrixXd& s) const override;
  double energy(const ArapElements::ValueRows& U) const override;

private:
  ArapElements::ValueRows forces_; // in U's order
  const std::vector<int>* position_;
  double f_dot_rest_;
};

// The terms of a solve, in the order their sums are formed: data's soft points (when it has any), then
// the forces (when forces has rows).
std::vector<std::unique_ptr<QuadraticTerm>> quadratic_terms(const ArapData& data,
                                                            const Eigen::MatrixXd& soft_targets,
                                                            const Eigen::MatrixXd& forces,
                                                            const std::vector<int>* position);

} // namespace iarap::detail
