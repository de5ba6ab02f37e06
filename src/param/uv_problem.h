// A UV map as a problem of the local/global engine (src/solver/problem.h): the free vertices' UV
// coordinates x (#free x 2), the energy W = E + barrier (uv_elastic_energy.h, injectivity_barrier.h; no
// barrier when flips are allowed), its gradient g = 2 (M U - r(R)) + grad barrier at the free rows, the
// preconditioner (2 M_ff)^{-1} (M factorized once with the pinned vertices held), so that x - P^{-1} g is
// the plain global step M_ff x = r_f - M_fc U_c, and the exact Hessian of min_R E (closed form in the
// plane) plus the barrier's. Flip-free, the plain step is that step shortened to the injectivity bound and
// halved until W decreases by Armijo's rule, and every line search of the engine stays within the bound:
// every iterate of every accelerator is injective. Internal to the param module.
#pragma once
#include "iarap/param/disk_mesh.h"
#include "iarap/solver/sparse_cholesky.h"

#include "../solver/constraint_layout.h"
#include "../solver/problem.h"
#include "injectivity_barrier.h"
#include "uv_elastic_energy.h"

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <memory>
#include <optional>
#include <vector>

namespace iarap::param_detail {

class UvProblem final : public detail::Problem {
public:
  // U (#V x 2): the start map, updated in place; pinned: the vertices held (sorted, distinct, at least
  // one). barrier: none for the plain iteration. disk and U must outlive the problem. Throws SolverError
  // when M_ff cannot be factorized.
  UvProblem(const DiskMesh& disk, std::unique_ptr<UvElasticEnergy> energy, const std::vector<int>& pinned,
            std::optional<InjectivityBarrier> barrier, Eigen::MatrixXd& U);

  Eigen::Index free_count() const override { return static_cast<Eigen::Index>(layout_.free.size()); }
  Eigen::Index dimension() const override { return 2; }
  Eigen::MatrixXd positions() const override;
  void set_positions(const Eigen::MatrixXd& x) override;
  double local_step() override;
  void assemble_rhs() override;
  const Eigen::MatrixXd& plain_step() override;
  const Eigen::MatrixXd& gradient() const override { return g_; }
  Eigen::MatrixXd solve(const Eigen::MatrixXd& r) const override;
  void prepare_hessian() override;
  Eigen::MatrixXd hessian_product(const Eigen::MatrixXd& v) override;
  double step_limit(const Eigen::MatrixXd& x, const Eigen::MatrixXd& d) const override;
  int solves() const override { return solves_; }

  // E (without the barrier) at the last local step.
  double elastic_energy() const { return E_; }
  FactorizationKind factorization() const { return cholesky_.kind(); }

private:
  Eigen::MatrixXd full(const Eigen::MatrixXd& x) const; // #V x 2, zero at the pinned rows
  Eigen::MatrixXd free_rows(const Eigen::MatrixXd& full) const;
  // step_limit from the point whose face Jacobians are J.
  double step_limit_from(const Eigen::MatrixXd& J, const Eigen::MatrixXd& d) const;

  const DiskMesh& disk_;
  std::unique_ptr<UvElasticEnergy> energy_;
  std::optional<InjectivityBarrier> barrier_;
  Eigen::MatrixXd& U_;
  detail::ConstraintLayout layout_; // the pinned vertices held, the free ones in order
  SparseCholesky cholesky_;         // M_ff
  // The state at the last local step: Jacobians, covariances, rotations, E and W; whether U is still there.
  Eigen::MatrixXd J_, S_, R_;
  double E_ = 0, W_ = 0;
  bool evaluated_ = false;
  // At the last assemble_rhs: the point, its Jacobians, W and the gradient; the plain step from there.
  Eigen::MatrixXd x_rhs_, J_rhs_, g_, plain_;
  double W_rhs_ = 0;
  // The Hessian at the last local step: per cell the quarter-turned rotation R_perp and 1 / |S_c|_sim.
  Eigen::MatrixXd R_perp_;
  Eigen::VectorXd inverse_norm_;
  mutable int solves_ = 0;
};

} // namespace iarap::param_detail
