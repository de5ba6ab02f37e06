#include "uv_elastic_energy.h"

#include "iarap/intrinsic/intrinsic_delaunay.h"
#include "iarap/mesh/cotan.h"
#include "iarap/solver/arap_elements.h"

#include <utility>

namespace iarap::param_detail {
namespace {

// Liu et al. 2008: sum_f area_f ||J_f - R_f||^2 = sum_f area_f (|J_f|^2 + 2) - 2 sum_f tr(R_f^T area_f J_f).
class TriangleEnergy final : public UvElasticEnergy {
public:
  explicit TriangleEnergy(const DiskMesh& disk) : disk_(disk), M_(cotan_laplacian(disk.V, disk.F)) {}

  const Eigen::SparseMatrix<double>& system() const override { return M_; }

  void covariances(const Eigen::MatrixXd& /*U*/, const Eigen::MatrixXd& J,
                   Eigen::MatrixXd& S) const override {
    S = J.array().colwise() * disk_.frames.area.array();
  }

  double energy(const Eigen::MatrixXd& /*U*/, const Eigen::MatrixXd& J,
                const Eigen::MatrixXd& R) const override {
    return ((J - R).rowwise().squaredNorm().array() * disk_.frames.area.array()).sum();
  }

  void scatter(const Eigen::MatrixXd& A, Eigen::MatrixXd& r) const override {
    r.setZero(disk_.V.rows(), 2);
    scatter_face_matrices(disk_, A, &disk_.frames.area, r);
  }

private:
  const DiskMesh& disk_;
  Eigen::SparseMatrix<double> M_;
};

// A per-vertex energy on flattened cells (planar_cells.h).
class CellEnergy final : public UvElasticEnergy {
public:
  explicit CellEnergy(PlanarCells cells)
      : cells_(std::move(cells)), M_(0.5 * element_system_matrix(cells_.elements)) {}

  const Eigen::SparseMatrix<double>& system() const override { return M_; }

  void covariances(const Eigen::MatrixXd& U, const Eigen::MatrixXd& /*J*/,
                   Eigen::MatrixXd& S) const override {
    planar_cell_covariances(cells_, U, S);
  }

  double energy(const Eigen::MatrixXd& U, const Eigen::MatrixXd& /*J*/,
                const Eigen::MatrixXd& R) const override {
    return planar_cell_energy_at(cells_, U, R);
  }

  void scatter(const Eigen::MatrixXd& A, Eigen::MatrixXd& r) const override { planar_cell_rhs(cells_, A, r); }

private:
  PlanarCells cells_;
  Eigen::SparseMatrix<double> M_;
};

PlanarCells cells_of(const DiskMesh& disk, ParamEnergy energy) {
  if (energy == ParamEnergy::Arap) return planar_cells(disk.V, disk.F, arap_edge_elements(disk.V, disk.F));
  IntrinsicOptions options; // the paper's discretization: no boundary refinement, every cell a vertex
  options.refine_boundary = false;
  options.assemble_B = false;
  options.keep_traces = false;
  return planar_cells(disk.V, disk.F, iarap_elements(disk.V, intrinsic_delaunay(disk.V, disk.F, options)));
}

} // namespace

void scatter_face_matrices(const DiskMesh& disk, const Eigen::MatrixXd& A, const Eigen::VectorXd* scale,
                           Eigen::MatrixXd& out) {
  const TriangleFrames& frames = disk.frames;
  for (Eigen::Index f = 0; f < disk.F.rows(); ++f) {
    const double a = scale ? (*scale)(f) : 1.0;
    for (int c = 0; c < 3; ++c) {
      const double dx = frames.D(f, 2 * c), dy = frames.D(f, 2 * c + 1);
      out(disk.F(f, c), 0) += a * (A(f, 0) * dx + A(f, 1) * dy);
      out(disk.F(f, c), 1) += a * (A(f, 2) * dx + A(f, 3) * dy);
    }
  }
}

std::unique_ptr<UvElasticEnergy> make_uv_elastic_energy(const DiskMesh& disk, ParamEnergy energy) {
  if (energy == ParamEnergy::Triangle) return std::make_unique<TriangleEnergy>(disk);
  return std::make_unique<CellEnergy>(cells_of(disk, energy));
}

} // namespace iarap::param_detail
