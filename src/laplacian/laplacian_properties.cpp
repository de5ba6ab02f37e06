#include "iarap/laplacian/laplacian_properties.h"

#include "iarap/core/errors.h"
#include "iarap/mesh/edge_topology.h"
#include "intrinsic_for_mesh.h"

#include <Eigen/Eigenvalues>
#include <Eigen/SVD>
#include <Eigen/SparseCholesky>
#include <Spectra/GenEigsRealShiftSolver.h>
#include <Spectra/MatOp/SparseGenRealShiftSolve.h>
#include <Spectra/SymEigsShiftSolver.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <vector>

namespace iarap {

namespace {

// Entries below this fraction of max |L_ii| are round-off: every entry is a sum of a few terms of
// magnitude <= max |L_ii|, each exact to ~1e-16 relative.
constexpr double kRelativeZero = 1e-12;
// Eigenvalues come from a Krylov method converged to ~1e-12 relative to the shifted spectrum.
constexpr double kPsdTolerance = 1e-9;
// "Flat" means every vertex within this fraction of the bounding-box diagonal of its best-fit plane.
constexpr double kFlatTolerance = 1e-12;

// (S - sigma I)^{-1} for Spectra's shift-invert mode, through a sparse Cholesky factorization: sigma is
// chosen below the Gershgorin bound, so S - sigma I is positive definite.
class SymShiftInverse {
public:
  using Scalar = double;
  explicit SymShiftInverse(const Eigen::SparseMatrix<double>& S) : S_(S) {}
  Eigen::Index rows() const { return S_.rows(); }
  Eigen::Index cols() const { return S_.cols(); }
  void set_shift(double sigma) {
    Eigen::SparseMatrix<double> I(S_.rows(), S_.cols());
    I.setIdentity();
    solver_.compute(S_ - sigma * I);
    if (solver_.info() != Eigen::Success)
      throw SolverError("Laplacian properties: Cholesky factorization of the shifted symmetric part failed");
  }
  void perform_op(const double* x_in, double* y_out) const {
    Eigen::Map<const Eigen::VectorXd> x(x_in, S_.rows());
    Eigen::Map<Eigen::VectorXd>(y_out, S_.rows()) = solver_.solve(x);
  }

private:
  Eigen::SparseMatrix<double> S_;
  Eigen::SimplicialLLT<Eigen::SparseMatrix<double>> solver_;
};

// min_i (L_ii - sum_{j != i} |L_ij|): no eigenvalue of L has a smaller real part (Gershgorin, rows).
double gershgorin_lower_bound(const Eigen::SparseMatrix<double>& L) {
  Eigen::VectorXd diagonal = Eigen::VectorXd::Zero(L.rows()), radius = Eigen::VectorXd::Zero(L.rows());
  for (int col = 0; col < L.outerSize(); ++col)
    for (Eigen::SparseMatrix<double>::InnerIterator it(L, col); it; ++it) {
      if (it.row() == it.col())
        diagonal(it.row()) += it.value();
      else
        radius(it.row()) += std::abs(it.value());
    }
  return L.rows() == 0 ? 0.0 : (diagonal - radius).minCoeff();
}

int krylov_dimension(Eigen::Index n, int nev) {
  return static_cast<int>(std::min<Eigen::Index>(n, std::max(2 * nev + 1, 30)));
}

// True when S + margin I is positive definite, i.e. every eigenvalue of S exceeds -margin: by Sylvester's
// law of inertia, when its LDL^T factorization has a positive D.
bool exceeds(const Eigen::SparseMatrix<double>& S, double margin) {
  Eigen::SparseMatrix<double> I(S.rows(), S.cols());
  I.setIdentity();
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt(S + margin * I);
  return ldlt.info() == Eigen::Success && (ldlt.vectorD().array() > 0.0).all();
}

// Smallest eigenvalue of the symmetric S: the one nearest to a shift below the whole spectrum. When S is
// PSD up to margin the shift -margin is below it and next to the (near-)zero eigenvalue, so shift-invert
// converges in a few steps; otherwise the Gershgorin bound gives a (slower) shift below the spectrum.
double smallest_eigenvalue(const Eigen::SparseMatrix<double>& S, double scale, bool psd_up_to_margin,
                           double margin) {
  if (S.rows() < 3) {
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> dense{Eigen::MatrixXd(S)};
    return dense.eigenvalues().minCoeff();
  }
  const double sigma = psd_up_to_margin ? -margin : std::min(gershgorin_lower_bound(S), 0.0) - 1e-3 * scale;
  SymShiftInverse op(S);
  Spectra::SymEigsShiftSolver<SymShiftInverse> eigs(op, 1, krylov_dimension(S.rows(), 1), sigma);
  eigs.init();
  eigs.compute(Spectra::SortRule::LargestMagn, 2000, 1e-12);
  if (eigs.info() != Spectra::CompInfo::Successful)
    throw SolverError("Laplacian properties: the smallest eigenvalue of the symmetric part did not converge");
  return eigs.eigenvalues()(0);
}

// Smallest real part among the eigenvalues of the (asymmetric) L nearest to sigma.
double smallest_real_part(const Eigen::SparseMatrix<double>& L, double sigma) {
  constexpr int nev = 4;
  if (L.rows() <= nev + 2) {
    Eigen::EigenSolver<Eigen::MatrixXd> dense{Eigen::MatrixXd(L), false};
    return dense.eigenvalues().real().minCoeff();
  }
  Spectra::SparseGenRealShiftSolve<double> op(L);
  Spectra::GenEigsRealShiftSolver<Spectra::SparseGenRealShiftSolve<double>> eigs(
      op, nev, krylov_dimension(L.rows(), nev), sigma);
  eigs.init();
  eigs.compute(Spectra::SortRule::LargestMagn, 2000, 1e-12);
  if (eigs.info() != Spectra::CompInfo::Successful)
    throw SolverError("Laplacian properties: the eigenvalues of L nearest to the shift did not converge");
  return eigs.eigenvalues().real().minCoeff();
}

// Sorted keys i * n + j of the off-diagonal pairs joined by an edge of E (both orders).
std::vector<long long> adjacency_keys(const Eigen::MatrixXi& E, long long n) {
  std::vector<long long> keys;
  keys.reserve(static_cast<size_t>(2 * E.rows()));
  for (Eigen::Index e = 0; e < E.rows(); ++e) {
    keys.push_back(E(e, 0) * n + E(e, 1));
    keys.push_back(E(e, 1) * n + E(e, 0));
  }
  std::sort(keys.begin(), keys.end());
  return keys;
}

bool within(const Eigen::SparseMatrix<double>& L, const std::vector<long long>& keys) {
  const long long n = L.rows();
  for (int col = 0; col < L.outerSize(); ++col)
    for (Eigen::SparseMatrix<double>::InnerIterator it(L, col); it; ++it)
      if (it.row() != it.col() && it.value() != 0.0 &&
          !std::binary_search(keys.begin(), keys.end(), it.row() * n + it.col()))
        return false;
  return true;
}

// Relative linear-precision residual (see the header), NaN when V is not planar.
double linear_precision_residual(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F,
                                 const Eigen::SparseMatrix<double>& L, double scale) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  if (V.rows() < 3)
    return nan;
  const double diagonal = (V.colwise().maxCoeff() - V.colwise().minCoeff()).norm();
  const Eigen::RowVector3d centroid = V.colwise().mean();
  const Eigen::MatrixXd centred = V.rowwise() - centroid;
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(centred.transpose() * centred, Eigen::ComputeFullU);
  const Eigen::Matrix3d frame = svd.matrixU(); // columns: in-plane directions, then the normal
  if ((centred * frame.col(2)).cwiseAbs().maxCoeff() > kFlatTolerance * diagonal)
    return nan;
  const EdgeTopology topology = edge_topology(F, static_cast<int>(V.rows()));
  std::vector<char> interior(static_cast<size_t>(V.rows()), 0);
  for (Eigen::Index f = 0; f < F.rows(); ++f)
    for (int k = 0; k < 3; ++k)
      interior[static_cast<size_t>(F(f, k))] = 1;
  for (Eigen::Index e = 0; e < topology.E.rows(); ++e)
    if (topology.face_count(e) == 1)
      interior[static_cast<size_t>(topology.E(e, 0))] = interior[static_cast<size_t>(topology.E(e, 1))] = 0;
  const Eigen::MatrixXd xy = centred * frame.leftCols(2);
  const Eigen::MatrixXd Lxy = L * xy;
  double residual = 0.0;
  for (Eigen::Index i = 0; i < V.rows(); ++i)
    if (interior[static_cast<size_t>(i)])
      residual = std::max(residual, Lxy.row(i).cwiseAbs().maxCoeff());
  return residual / (scale * diagonal);
}

} // namespace

LaplacianProperties laplacian_properties(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F,
                                         const Eigen::SparseMatrix<double>& L, const std::string& kind,
                                         const IntrinsicDelaunay* idt) {
  if (L.rows() != V.rows() || L.cols() != V.rows())
    throw InputError("Laplacian is " + std::to_string(L.rows()) + " x " + std::to_string(L.cols()) + " for " +
                     std::to_string(V.rows()) + " vertices");
  LaplacianProperties p;
  p.kind = kind;
  const auto n = static_cast<long long>(V.rows());

  Eigen::VectorXd row_sum = Eigen::VectorXd::Zero(V.rows());
  double scale = 0.0;
  for (int col = 0; col < L.outerSize(); ++col)
    for (Eigen::SparseMatrix<double>::InnerIterator it(L, col); it; ++it) {
      row_sum(it.row()) += it.value();
      if (it.row() == it.col())
        scale = std::max(scale, std::abs(it.value()));
    }
  p.diagonal_max_abs = scale;
  if (scale == 0.0)
    scale = 1.0; // an empty operator: relative figures become absolute
  p.row_sum_max_abs = V.rows() == 0 ? 0.0 : row_sum.cwiseAbs().maxCoeff();

  const Eigen::SparseMatrix<double> Lt = L.transpose();
  const Eigen::SparseMatrix<double> asymmetry = L - Lt;
  for (int col = 0; col < asymmetry.outerSize(); ++col)
    for (Eigen::SparseMatrix<double>::InnerIterator it(asymmetry, col); it; ++it)
      p.symmetry_error = std::max(p.symmetry_error, std::abs(it.value()) / scale);
  p.symmetric = p.symmetry_error <= kRelativeZero;

  for (int col = 0; col < L.outerSize(); ++col)
    for (Eigen::SparseMatrix<double>::InnerIterator it(L, col); it; ++it)
      if (it.row() != it.col() && it.value() > kRelativeZero * scale) {
        ++p.negative_offdiag_count;
        p.negative_offdiag_max_abs = std::max(p.negative_offdiag_max_abs, it.value());
        p.negative_offdiag_sum_abs += it.value();
      }
  p.positive_weights = p.negative_offdiag_count == 0;

  p.sparsity_within_input_adjacency = within(L, adjacency_keys(edge_topology(F, static_cast<int>(n)).E, n));
  if (idt)
    p.sparsity_within_intrinsic_adjacency = within(L, adjacency_keys(idt->triangulation.E, n));
  p.weakly_local = p.sparsity_within_input_adjacency || p.sparsity_within_intrinsic_adjacency;
  // Strong locality by construction: every operator but the extrinsic cotan one reads its weights from
  // the intrinsic Delaunay triangulation, which is global (see the header).
  p.strongly_local = kind == laplacian_kind_name(LaplacianKind::Cotan) && p.sparsity_within_input_adjacency;

  p.linear_precision_residual = linear_precision_residual(V, F, L, scale);

  const Eigen::SparseMatrix<double> S = 0.5 * (L + Lt);
  p.psd = V.rows() == 0 || exceeds(S, kPsdTolerance * scale);
  p.min_eigenvalue = V.rows() == 0 ? 0.0 : smallest_eigenvalue(S, scale, p.psd, kPsdTolerance * scale);
  const double bound = gershgorin_lower_bound(L);
  p.gershgorin_real_part_bound = bound / scale;
  if (p.symmetric || V.rows() == 0)
    p.min_real_part = p.min_eigenvalue;
  else
    p.min_real_part = smallest_real_part(L, std::min(bound, 0.0) - 1e-3 * scale);
  return p;
}

LaplacianProperties laplacian_properties(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F,
                                         LaplacianKind kind, const IntrinsicDelaunay* precomputed) {
  std::optional<IntrinsicDelaunay> storage;
  const IntrinsicDelaunay& idt = detail::intrinsic_for_mesh(V, F, precomputed, storage);
  return laplacian_properties(V, F, laplacian(V, F, kind, &idt), laplacian_kind_name(kind), &idt);
}

} // namespace iarap
