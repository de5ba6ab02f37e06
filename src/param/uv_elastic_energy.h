// The elastic term of a UV map's energy, one 2x2 rotation per cell: E(U) = min_R sum_c e_c(U, R_c), where
// for a fixed R it is quadratic with the rotations entering linearly,
//   E(U; R) = tr(U^T M U) - 2 sum_c tr(R_c^T S_c(U)) + const,   S_c linear in U,
// so that grad E = 2 (M U - r(R)) with r(R) = sum_c d/dU tr(R_c^T S_c(U)) (the global step solves M U = r)
// and R_c = closest_rotation_2d(S_c). In the plane min_R has a closed form, E = const + tr(U^T M U)
// - 2 sum_c |S_c|_sim with |S|_sim = |(S00 + S11, S10 - S01)|, whose Hessian is exact and cheap (UvProblem).
// Two kinds: Liu et al.'s per-triangle energy (cells = faces, S_f = area_f J_f, M = the cotan Laplacian)
// and the per-vertex energies of planar_cells.h (cells = vertices, M = element_system_matrix / 2).
// Internal to the param module.
#pragma once
#include "iarap/param/disk_mesh.h"
#include "iarap/param/param_options.h"
#include "iarap/param/planar_cells.h"

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <memory>

namespace iarap::param_detail {

class UvElasticEnergy {
public:
  virtual ~UvElasticEnergy() = default;
  // M, #V x #V.
  virtual const Eigen::SparseMatrix<double>& system() const = 0;
  // S (#cells x 4, row by row) of U (#V x 2); J (#F x 4) are U's face Jacobians (the triangle kind reads
  // them, the cell kind U).
  virtual void covariances(const Eigen::MatrixXd& U, const Eigen::MatrixXd& J, Eigen::MatrixXd& S) const = 0;
  // E(U; R) for rotations R (#cells x 4).
  virtual double energy(const Eigen::MatrixXd& U, const Eigen::MatrixXd& J,
                        const Eigen::MatrixXd& R) const = 0;
  // r(A) = sum_c d/dU tr(A_c^T S_c(U)) for any A (#cells x 4), into r (#V x 2): linear in A.
  virtual void scatter(const Eigen::MatrixXd& A, Eigen::MatrixXd& r) const = 0;
};

// out (#V x 2) += per face f and corner c, row F(f, c): (A_f D_f^T) column c, A_f = A.row(f) as a 2x2
// matrix times scale(f): d/dU sum_f scale(f) tr(A_f^T J_f(U)). The gradient pattern of every per-face term.
void scatter_face_matrices(const DiskMesh& disk, const Eigen::MatrixXd& A, const Eigen::VectorXd* scale,
                           Eigen::MatrixXd& out);

// The elastic term of `energy` on the disk: the triangle kind, or the per-vertex kind on the cells of
// original ARAP's edges or iARAP's segments (the paper's discretization, no boundary refinement).
std::unique_ptr<UvElasticEnergy> make_uv_elastic_energy(const DiskMesh& disk, ParamEnergy energy);

} // namespace iarap::param_detail
