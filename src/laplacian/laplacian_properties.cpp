#include "iarap/laplacian/laplacian_properties.h"

#include "iarap/core/errors.h"
#include "iarap/mesh/edge_topology.h"
#include "intrinsic_for_mesh.h"

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <Eigen/SVD>
#include <Eigen/SparseCholesky>
#include <Spectra/GenEigsRealShiftSolver.h>
#include <Spectra/MatOp/SparseGenRealShiftSolve.h>
#include <Spectra/SymEigsShiftSolver.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <utility>
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
// Strong locality: an operator equal to the cotan Laplacian up to the round-off of its construction
// (<= 1e-12 of max |L_ii| on every mesh measured, see operator_identity_test.cpp) leaks at most that much;
// an operator that reads the (global) intrinsic triangulation changes entries far away by 1e-4 and more
// when a probe moves by 5% of an altitude. 1e-9 sits three orders of magnitude from both.
constexpr double kLeakTolerance = 1e-9;
constexpr double kProbeStep = 0.05; // probe displacement, as a fraction of the vertex's smallest altitude
constexpr int kProbes = 4;

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

// Probe vertices for strong locality: those whose input star the most traced segments of intrinsic
// edges not incident to them cross (a far-away edge changes when they move), up to kProbes; on a mesh
// without such crossings (Delaunay) three vertices spread over the index range.
std::vector<int> locality_probes(const IntrinsicDelaunay* idt, int num_vertices) {
  std::vector<int> crossings(static_cast<size_t>(num_vertices), 0);
  if (idt) {
    const Segments& s = idt->segments;
    const Eigen::MatrixXi& E = idt->triangulation.E;
    for (Eigen::Index k = 0; k < s.edge.size(); ++k)
      for (int slot = 0; slot < 3; ++slot) {
        const int v = s.b_index(k, slot);
        if (s.b_value(k, slot) != 0.0 && v < num_vertices && v != E(s.edge(k), 0) && v != E(s.edge(k), 1))
          ++crossings[static_cast<size_t>(v)];
      }
  }
  std::vector<int> order(static_cast<size_t>(num_vertices));
  for (int v = 0; v < num_vertices; ++v) order[static_cast<size_t>(v)] = v;
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) {
    return crossings[static_cast<size_t>(a)] > crossings[static_cast<size_t>(b)];
  });
  std::vector<int> probes;
  for (int v : order)
    if (static_cast<int>(probes.size()) < kProbes && crossings[static_cast<size_t>(v)] > 0)
      probes.push_back(v);
  if (probes.empty() && num_vertices > 0) probes = {0, num_vertices / 2, num_vertices - 1};
  return probes;
}

// V with vertex k moved by kProbeStep x its smallest altitude in its faces along a fixed generic
// direction: less than every altitude, so no incident triangle degenerates (the distance to a line is
// 1-Lipschitz).
Eigen::MatrixXd moved_probe(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, int k) {
  double altitude = std::numeric_limits<double>::infinity();
  for (Eigen::Index f = 0; f < F.rows(); ++f)
    for (int c = 0; c < 3; ++c)
      if (F(f, c) == k) {
        const Eigen::Vector3d a = V.row(F(f, c)), b = V.row(F(f, (c + 1) % 3)), d = V.row(F(f, (c + 2) % 3));
        altitude = std::min(altitude, (b - a).cross(d - a).norm() / (d - b).norm());
      }
  Eigen::MatrixXd moved = V;
  if (std::isfinite(altitude)) moved.row(k) += kProbeStep * altitude * Eigen::RowVector3d(0.48, 0.6, 0.64);
  return moved;
}

// Largest |L_moved(i,j) - L(i,j)| over entries with i or j outside the closed input 1-ring of k.
double leak_outside_ring(const Eigen::SparseMatrix<double>& L, const Eigen::SparseMatrix<double>& L_moved,
                         const Eigen::MatrixXi& F, int k) {
  std::vector<char> ring(static_cast<size_t>(L.rows()), 0);
  ring[static_cast<size_t>(k)] = 1;
  for (Eigen::Index f = 0; f < F.rows(); ++f)
    if (F(f, 0) == k || F(f, 1) == k || F(f, 2) == k)
      for (int c = 0; c < 3; ++c) ring[static_cast<size_t>(F(f, c))] = 1;
  const Eigen::SparseMatrix<double> change = L_moved - L;
  double leak = 0.0;
  for (int col = 0; col < change.outerSize(); ++col)
    for (Eigen::SparseMatrix<double>::InnerIterator it(change, col); it; ++it)
      if (!ring[static_cast<size_t>(it.row())] || !ring[static_cast<size_t>(it.col())])
        leak = std::max(leak, std::abs(it.value()));
  return leak;
}

// Sorted keys i * n + j (both orders) of the input boundary edges, and of those among them that are
// intrinsic boundary edges with a negative cotan weight (obtuse opposite angle after flipping).
std::pair<std::vector<long long>, std::vector<long long>> boundary_keys(const Eigen::MatrixXi& F, long long n,
                                                                        const IntrinsicDelaunay* idt) {
  const EdgeTopology topology = edge_topology(F, static_cast<int>(n));
  Eigen::MatrixXi boundary(topology.E.rows(), 2);
  Eigen::Index count = 0;
  for (Eigen::Index e = 0; e < topology.E.rows(); ++e)
    if (topology.face_count(e) == 1) boundary.row(count++) = topology.E.row(e);
  std::vector<long long> obtuse;
  if (idt) {
    const IntrinsicTriangulation& T = idt->triangulation;
    Eigen::MatrixXi negative(T.E.rows(), 2);
    Eigen::Index m = 0;
    for (Eigen::Index e = 0; e < T.E.rows(); ++e)
      if (T.is_boundary(e) && T.cot_weight(e) < 0.0 && T.E(e, 0) < n && T.E(e, 1) < n)
        negative.row(m++) = T.E.row(e);
    obtuse = adjacency_keys(negative.topRows(m), n);
  }
  return {adjacency_keys(boundary.topRows(count), n), obtuse};
}

// Relative linear-precision residual (see the header), NaN when V is not planar.
double linear_precision_residual(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F,
                                 const Eigen::SparseMatrix<double>& L, double scale) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  if (V.rows() < 3) return nan;
  const double diagonal = (V.colwise().maxCoeff() - V.colwise().minCoeff()).norm();
  const Eigen::RowVector3d centroid = V.colwise().mean();
  const Eigen::MatrixXd centred = V.rowwise() - centroid;
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(centred.transpose() * centred, Eigen::ComputeFullU);
  const Eigen::Matrix3d frame = svd.matrixU(); // columns: in-plane directions, then the normal
  if ((centred * frame.col(2)).cwiseAbs().maxCoeff() > kFlatTolerance * diagonal) return nan;
  const EdgeTopology topology = edge_topology(F, static_cast<int>(V.rows()));
  std::vector<char> interior(static_cast<size_t>(V.rows()), 0);
  for (Eigen::Index f = 0; f < F.rows(); ++f)
    for (int k = 0; k < 3; ++k) interior[static_cast<size_t>(F(f, k))] = 1;
  for (Eigen::Index e = 0; e < topology.E.rows(); ++e)
    if (topology.face_count(e) == 1)
      interior[static_cast<size_t>(topology.E(e, 0))] = interior[static_cast<size_t>(topology.E(e, 1))] = 0;
  const Eigen::MatrixXd xy = centred * frame.leftCols(2);
  const Eigen::MatrixXd Lxy = L * xy;
  double residual = 0.0;
  for (Eigen::Index i = 0; i < V.rows(); ++i)
    if (interior[static_cast<size_t>(i)]) residual = std::max(residual, Lxy.row(i).cwiseAbs().maxCoeff());
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
      if (it.row() == it.col()) scale = std::max(scale, std::abs(it.value()));
    }
  p.diagonal_max_abs = scale;
  if (scale == 0.0) scale = 1.0; // an empty operator: relative figures become absolute
  p.row_sum_max_abs = V.rows() == 0 ? 0.0 : row_sum.cwiseAbs().maxCoeff();

  const Eigen::SparseMatrix<double> Lt = L.transpose();
  const Eigen::SparseMatrix<double> asymmetry = L - Lt;
  for (int col = 0; col < asymmetry.outerSize(); ++col)
    for (Eigen::SparseMatrix<double>::InnerIterator it(asymmetry, col); it; ++it)
      p.symmetry_error = std::max(p.symmetry_error, std::abs(it.value()) / scale);
  p.symmetric = p.symmetry_error <= kRelativeZero;

  const auto [boundary, obtuse_boundary] = boundary_keys(F, n, idt);
  for (int col = 0; col < L.outerSize(); ++col)
    for (Eigen::SparseMatrix<double>::InnerIterator it(L, col); it; ++it)
      if (it.row() != it.col() && it.value() > kRelativeZero * scale) {
        ++p.negative_offdiag_count;
        p.negative_offdiag_max_abs = std::max(p.negative_offdiag_max_abs, it.value());
        p.negative_offdiag_sum_abs += it.value();
        const long long key = it.row() * n + it.col();
        p.negative_offdiag_on_boundary += std::binary_search(boundary.begin(), boundary.end(), key);
        p.negative_offdiag_on_obtuse_boundary +=
            std::binary_search(obtuse_boundary.begin(), obtuse_boundary.end(), key);
      }
  p.positive_weights = p.negative_offdiag_count == 0;

  p.sparsity_within_input_adjacency = within(L, adjacency_keys(edge_topology(F, static_cast<int>(n)).E, n));
  if (idt) p.sparsity_within_intrinsic_adjacency = within(L, adjacency_keys(idt->triangulation.E, n));
  p.weakly_local = p.sparsity_within_input_adjacency || p.sparsity_within_intrinsic_adjacency;
  // Strong locality, measured (see the header): rebuild the operator with one probe vertex moved.
  const auto known = std::find_if(all_laplacian_kinds().begin(), all_laplacian_kinds().end(),
                                  [&](LaplacianKind k) { return laplacian_kind_name(k) == kind; });
  if (known != all_laplacian_kinds().end()) {
    for (int k : locality_probes(idt, static_cast<int>(n))) {
      const Eigen::SparseMatrix<double> moved = laplacian(moved_probe(V, F, k), F, *known);
      p.strong_locality_leak = std::max(p.strong_locality_leak, leak_outside_ring(L, moved, F, k) / scale);
      ++p.strong_locality_probes;
    }
  }
  p.strongly_local = p.strong_locality_probes > 0 && p.sparsity_within_input_adjacency &&
                     p.strong_locality_leak <= kLeakTolerance;

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
  p.eigenvalues_nonnegative_real_part =
      p.gershgorin_real_part_bound >= -kRelativeZero || p.min_real_part >= -kPsdTolerance * scale;
  return p;
}

LaplacianProperties laplacian_properties(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F,
                                         LaplacianKind kind, const IntrinsicDelaunay* precomputed) {
  std::optional<IntrinsicDelaunay> storage;
  const IntrinsicDelaunay& idt = detail::intrinsic_for_mesh(V, F, precomputed, storage);
  return laplacian_properties(V, F, laplacian(V, F, kind, &idt), laplacian_kind_name(kind), &idt);
}

} // namespace iarap
