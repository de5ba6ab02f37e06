#include "iarap/solver/sparse_cholesky.h"

#include "iarap/core/blas_library.h"
#include "iarap/core/errors.h"
#include "iarap/core/threads.h"
#include "metis_ordering.h"
#include "supernodal_solve.h"

#include <omp.h>

#include <Eigen/CholmodSupport>
#include <Eigen/SparseCholesky>
#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

namespace iarap {

namespace {
// An LDL^T pivot this small relative to the largest means A is singular to working precision.
constexpr double kPivotTolerance = 1e-14;

// CHOLMOD as Debian builds it (SuiteSparse 5.12) opens OpenMP teams of a fixed 4 threads inside its
// supernodal factorization, whatever thread count the caller set; on fewer cores they oversubscribe them
// (beetle's factorization, --threads 1 on 2 cores: 25 ms serialized against 34 ms). While one of these
// lives, CHOLMOD's teams run serialized unless 4 threads are allowed; nothing else changes (the setting is
// the calling task's and restored after).
class CholmodTeams {
public:
  CholmodTeams() : saved_(omp_get_max_active_levels()) {
    if (thread_count() < 4) omp_set_max_active_levels(omp_get_active_level());
  }
  ~CholmodTeams() { omp_set_max_active_levels(saved_); }
  CholmodTeams(const CholmodTeams&) = delete;
  CholmodTeams& operator=(const CholmodTeams&) = delete;

private:
  int saved_;
};
} // namespace

namespace {
// One fill-reducing ordering, chosen by the caller, instead of CHOLMOD's default (AMD, then METIS as well
// when AMD's fill is high): measured on the armadillo subdivided 2 and 3 times (docs/performance.md), AMD
// orders in a quarter of METIS's time and METIS's factor has 25-40% fewer entries, factorized faster.
// ordering: Amd or Metis (resolved).
void configure_ordering(cholmod_common& common, FillOrdering ordering) {
  common.nmethods = 1;
  common.method[0].ordering = ordering == FillOrdering::Metis ? CHOLMOD_METIS : CHOLMOD_AMD;
  common.postorder = 1;
  common.print = 0; // "not positive definite" is an expected outcome, not a warning to print
}

// Eigen's wrapper with its CHOLMOD factor in reach, for cholmod_solve2 (Eigen's solve allocates per call).
class CholmodLlt : public Eigen::CholmodSupernodalLLT<Eigen::SparseMatrix<double>> {
public:
  cholmod_factor* factor() const { return m_cholmodFactor; }

  // analyzePattern(matrix), its fill-reducing ordering given (CHOLMOD postorders it): Eigen's analyzePattern
  // with cholmod_analyze_p in place of cholmod_analyze.
  void analyze_given(const Eigen::SparseMatrix<double>& matrix, std::vector<int>& perm) {
    cholmod_common& common = cholmod();
    if (m_cholmodFactor) cholmod_free_factor(&m_cholmodFactor, &common);
    common.nmethods = 1;
    common.method[0].ordering = CHOLMOD_GIVEN;
    cholmod_sparse A = Eigen::viewAsCholmod(matrix.selfadjointView<Eigen::Lower>());
    m_cholmodFactor = cholmod_analyze_p(&A, perm.data(), nullptr, 0, &common);
    m_isInitialized = true;
    m_info = m_cholmodFactor ? Eigen::Success : Eigen::NumericalIssue;
    m_analysisIsOk = m_cholmodFactor != nullptr;
    m_factorizationIsOk = false;
  }
};

// The symbolic analysis of llt on `pattern` with `ordering` (resolved). METIS is called directly
// (metis_ordering.h: cheaper options, no A + A^T) where it can be; CHOLMOD's own ordering otherwise.
void analyze_pattern(CholmodLlt& llt, const Eigen::SparseMatrix<double>& pattern, FillOrdering ordering) {
  configure_ordering(llt.cholmod(), ordering);
  if (ordering == FillOrdering::Metis) {
    std::vector<int> perm = detail::metis_nested_dissection(pattern);
    if (!perm.empty()) {
      llt.analyze_given(pattern, perm);
      return;
    }
  }
  llt.analyzePattern(pattern);
}

// cholmod_solve2's solution and workspaces, allocated by CHOLMOD on the first solve and reused after.
// Freed with the CHOLMOD common of the factor that allocated them, before that factor goes.
struct SolveWorkspace {
  cholmod_common* common = nullptr;
  cholmod_dense *X = nullptr, *Y = nullptr, *E = nullptr;
  void release() {
    if (common)
      for (cholmod_dense** d : {&X, &Y, &E})
        if (*d) cholmod_free_dense(d, common);
    X = Y = E = nullptr;
  }
};

// cholmod_solve2 of A X = B into the workspace's X.
void cholmod_solve_into(cholmod_factor* factor, const Eigen::MatrixXd& B, SolveWorkspace& ws) {
  // A CHOLMOD view of B (column-major, leading dimension = rows); CHOLMOD only reads it.
  cholmod_dense b{};
  b.nrow = static_cast<size_t>(B.rows());
  b.ncol = static_cast<size_t>(B.cols());
  b.nzmax = b.nrow * b.ncol;
  b.d = b.nrow;
  b.x = const_cast<double*>(B.data());
  b.xtype = CHOLMOD_REAL;
  b.dtype = CHOLMOD_DOUBLE;
  if (!cholmod_solve2(CHOLMOD_A, factor, &b, nullptr, &ws.X, nullptr, &ws.Y, &ws.E, ws.common))
    throw SolverError("sparse Cholesky: CHOLMOD's solve failed (status " + std::to_string(ws.common->status) +
                      ")");
}

// The hand-written solve's plan for llt's factor; null when the factor is not of the kind it reads
// (CHOLMOD's own solve then).
std::unique_ptr<detail::SupernodalSolve> supernodal_plan(const cholmod_factor* L) {
  const auto view = detail::supernodal_factor_view(L);
  if (!view) return nullptr;
  auto plan = std::make_unique<detail::SupernodalSolve>(*view, thread_count());
  if (!plan->usable()) return nullptr;
  return plan;
}

} // namespace

namespace {
// Eigen's simplicial LLT with its AMD ordering (a port of CSparse's minimum degree): on the ogre's charts it
// ordered in less time than SuiteSparse's amd_order (the ordering CHOLMOD runs), 237 against 323 perf
// samples of one run each; the natural order filled the factors (3.5 x the whole atlas's time).
using SimplicialLlt =
    Eigen::SimplicialLLT<Eigen::SparseMatrix<double>, Eigen::Lower, Eigen::AMDOrdering<int>>;
} // namespace

struct SparseCholesky::Impl {
  // The lower triangle of the factorized matrix (all that is read of it), kept so that copies can
  // refactorize and a refactorization can tell its pattern: half the bytes of the whole (issue 44).
  Eigen::SparseMatrix<double> A;
  FactorizationKind kind = FactorizationKind::None;
  FillOrdering ordering = FillOrdering::Auto;
  FillOrdering used = FillOrdering::Amd; // what the last analysis ran
  Eigen::SparseMatrix<double> analyzed;  // the pattern llt was analyzed on (analyze()), values unused
  std::unique_ptr<CholmodLlt> llt;
  std::unique_ptr<Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>>> ldlt;
  Eigen::Index simplicial_below = 0; // set_simplicial_below
  std::unique_ptr<SimplicialLlt> simplicial;
  SolveWorkspace workspace;
  // The hand-written supernodal solve over llt's factor (null: cholmod_solve2 instead) and its workspaces.
  std::unique_ptr<detail::SupernodalSolve> supernodal;
  detail::SupernodalWorkspace supernodal_workspace;

  Impl() = default;
  Impl(Impl&& other) noexcept { *this = std::move(other); }
  // The workspace goes before the factor whose CHOLMOD common allocated it.
  Impl& operator=(Impl&& other) noexcept {
    if (this == &other) return *this;
    workspace.release();
    // Swapped, not assigned: Eigen 3.4's SparseMatrix has no move assignment (it would copy), and its
    // assignment from an empty matrix keeps the capacity. other (a temporary or a discarded Impl) frees them.
    A.swap(other.A);
    kind = other.kind;
    ordering = other.ordering;
    used = other.used;
    analyzed.swap(other.analyzed);
    llt = std::move(other.llt);
    ldlt = std::move(other.ldlt);
    simplicial_below = other.simplicial_below;
    simplicial = std::move(other.simplicial);
    workspace = other.workspace;
    other.workspace = SolveWorkspace{};
    supernodal = std::move(other.supernodal);
    supernodal_workspace = std::move(other.supernodal_workspace);
    return *this;
  }
  ~Impl() { workspace.release(); }
};

std::string factorization_name(FactorizationKind kind) {
  switch (kind) {
  case FactorizationKind::None:
    return "none";
  case FactorizationKind::Empty:
    return "empty";
  case FactorizationKind::CholmodSupernodalLLT:
    return "cholmod-supernodal-llt";
  case FactorizationKind::SimplicialLDLT:
    return "simplicial-ldlt";
  case FactorizationKind::SimplicialLLT:
    return "simplicial-llt";
  }
  return "unknown";
}

FillOrdering resolved_ordering(FillOrdering ordering, long n) {
  if (ordering != FillOrdering::Auto) return ordering;
  return n >= auto_metis_rows ? FillOrdering::Metis : FillOrdering::Amd;
}

FillOrdering parse_fill_ordering(const std::string& name) {
  if (name == "auto") return FillOrdering::Auto;
  if (name == "amd") return FillOrdering::Amd;
  if (name == "metis") return FillOrdering::Metis;
  throw InputError("unknown fill ordering '" + name + "' (choose auto, amd or metis)");
}

std::string fill_ordering_name(FillOrdering ordering) {
  switch (ordering) {
  case FillOrdering::Auto:
    return "auto";
  case FillOrdering::Amd:
    return "amd";
  case FillOrdering::Metis:
    return "metis";
  }
  return "unknown";
}

SparseCholesky::SparseCholesky() : impl_(std::make_unique<Impl>()) {}

SparseCholesky::SparseCholesky(const Eigen::SparseMatrix<double>& A) : SparseCholesky() {
  factorize(A);
}

SparseCholesky::SparseCholesky(const SparseCholesky& other) : SparseCholesky() {
  if (!other.impl_) return;
  impl_->ordering = other.impl_->ordering;
  impl_->simplicial_below = other.impl_->simplicial_below;
  if (other.impl_->kind != FactorizationKind::None) factorize(other.impl_->A);
}

SparseCholesky& SparseCholesky::operator=(const SparseCholesky& other) {
  if (this != &other) *this = SparseCholesky(other);
  return *this;
}

SparseCholesky::SparseCholesky(SparseCholesky&&) noexcept = default;
SparseCholesky& SparseCholesky::operator=(SparseCholesky&&) noexcept = default;
SparseCholesky::~SparseCholesky() = default;

namespace {
// True when the compressed a and b have the same entries on and below the diagonal (where the
// factorization reads them; either may hold its upper triangle too).
bool same_lower_pattern(const Eigen::SparseMatrix<double>& a, const Eigen::SparseMatrix<double>& b) {
  if (!a.isCompressed() || !b.isCompressed() || a.rows() != b.rows() || a.cols() != b.cols()) return false;
  // Column j's rows from j on: its inner indices are ascending in a compressed matrix.
  const auto lower_part = [](const Eigen::SparseMatrix<double>& m, int j) {
    const int* first = m.innerIndexPtr() + m.outerIndexPtr()[j];
    const int* last = m.innerIndexPtr() + m.outerIndexPtr()[j + 1];
    return std::make_pair(std::lower_bound(first, last, j), last);
  };
  for (int j = 0; j < a.outerSize(); ++j) {
    const auto [a_first, a_last] = lower_part(a, j);
    const auto [b_first, b_last] = lower_part(b, j);
    if (!std::equal(a_first, a_last, b_first, b_last)) return false;
  }
  return true;
}
} // namespace

void SparseCholesky::set_ordering(FillOrdering ordering) {
  if (!impl_) impl_ = std::make_unique<Impl>();
  impl_->ordering = ordering;
}

void SparseCholesky::set_simplicial_below(Eigen::Index rows) {
  if (!impl_) impl_ = std::make_unique<Impl>();
  impl_->simplicial_below = rows;
}

Eigen::Index SparseCholesky::simplicial_below() const {
  return impl_ ? impl_->simplicial_below : 0;
}

FillOrdering SparseCholesky::ordering() const {
  return impl_ ? impl_->ordering : FillOrdering::Auto;
}

FillOrdering SparseCholesky::used_ordering() const {
  if (!impl_) return resolved_ordering(FillOrdering::Auto, 0);
  return impl_->llt ? impl_->used : resolved_ordering(impl_->ordering, impl_->A.rows());
}

void SparseCholesky::analyze(const Eigen::SparseMatrix<double>& pattern) {
  const FillOrdering ordering = this->ordering();
  const Eigen::Index simplicial_below = this->simplicial_below();
  if (!impl_) impl_ = std::make_unique<Impl>();
  *impl_ = Impl{};
  impl_->ordering = ordering;
  impl_->simplicial_below = simplicial_below;
  if (pattern.rows() != pattern.cols() || pattern.rows() == 0 || !pattern.isCompressed())
    return; // factorize() reports a non-square matrix; nothing to analyze for an empty one
  impl_->analyzed = pattern;
  impl_->llt = std::make_unique<CholmodLlt>();
  impl_->used = resolved_ordering(ordering, pattern.rows());
  const CholmodTeams teams;
  analyze_pattern(*impl_->llt, impl_->analyzed, impl_->used);
}

void SparseCholesky::factorize(const Eigen::SparseMatrix<double>& A) {
  const FillOrdering ordering = this->ordering();
  const Eigen::Index simplicial_below = this->simplicial_below();
  if (!impl_) impl_ = std::make_unique<Impl>();
  // Reuse the symbolic analysis only for exactly the analyzed pattern: analyze()'s, or that of the matrix
  // the last LLT factorized (a numeric refactorization, e.g. new soft weights).
  std::unique_ptr<CholmodLlt> analyzed;
  const FillOrdering analyzed_with = impl_->used;
  if (impl_->llt && same_lower_pattern(impl_->analyzed.nonZeros() > 0 ? impl_->analyzed : impl_->A, A))
    analyzed = std::move(impl_->llt);
  *impl_ = Impl{};
  if (A.rows() != A.cols())
    throw SolverError("sparse Cholesky: matrix is " + std::to_string(A.rows()) + " x " +
                      std::to_string(A.cols()) + ", not square");
  for (int k = 0; k < A.outerSize(); ++k)
    for (Eigen::SparseMatrix<double>::InnerIterator it(A, k); it; ++it)
      if (!std::isfinite(it.value()))
        throw SolverError("sparse Cholesky: entry (" + std::to_string(it.row()) + ", " +
                          std::to_string(it.col()) + ") is not finite");
  Impl next;
  next.ordering = ordering;
  next.simplicial_below = simplicial_below;
  next.A = A.triangularView<Eigen::Lower>();
  next.A.makeCompressed();
  if (A.rows() == 0) {
    next.kind = FactorizationKind::Empty;
    *impl_ = std::move(next);
    return;
  }

  if (next.A.rows() < simplicial_below) {
    next.simplicial = std::make_unique<SimplicialLlt>(next.A);
    if (next.simplicial->info() == Eigen::Success) {
      next.kind = FactorizationKind::SimplicialLLT;
      *impl_ = std::move(next);
      return;
    }
    next.simplicial.reset(); // not positive definite (CHOLMOD's LLT would fail as well): LDL^T below
  } else {
    const CholmodTeams teams;
    limit_blas_threads(loop_thread_count());
    if (analyzed) {
      next.llt = std::move(analyzed);
      next.used = analyzed_with;
      next.llt->factorize(next.A);
    } else {
      next.llt = std::make_unique<CholmodLlt>();
      next.used = resolved_ordering(ordering, next.A.rows());
      analyze_pattern(*next.llt, next.A, next.used);
      if (next.llt->info() == Eigen::Success) next.llt->factorize(next.A);
    }
    if (next.llt->info() == Eigen::Success) {
      // CHOLMOD's workspaces (sized by the rows and the supernodes) serve the next analysis or
      // factorization only; a solve allocates what it needs.
      cholmod_free_work(&next.llt->cholmod());
      next.kind = FactorizationKind::CholmodSupernodalLLT;
      next.supernodal = supernodal_plan(next.llt->factor());
      *impl_ = std::move(next);
      return;
    }
    next.llt.reset();
  }

  // Indefinite but possibly nonsingular (negative cotan or iARAP boundary weights): LDL^T.
  next.ldlt = std::make_unique<Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>>>(next.A);
  if (next.ldlt->info() != Eigen::Success)
    throw SolverError("sparse Cholesky: the " + std::to_string(A.rows()) + " x " + std::to_string(A.rows()) +
                      " matrix is singular (zero pivot in LDL^T)");
  const Eigen::VectorXd D = next.ldlt->vectorD();
  const double largest = D.cwiseAbs().maxCoeff();
  Eigen::Index row = 0;
  const double smallest = D.cwiseAbs().minCoeff(&row);
  if (!(smallest > kPivotTolerance * largest))
    throw SolverError("sparse Cholesky: the " + std::to_string(A.rows()) + " x " + std::to_string(A.rows()) +
                      " matrix is numerically singular (LDL^T pivot " + std::to_string(smallest) +
                      " vs largest " + std::to_string(largest) + ", permuted row " + std::to_string(row) +
                      ")");
  next.kind = FactorizationKind::SimplicialLDLT;
  *impl_ = std::move(next);
}

namespace {
// The triangular solves of simplicial_solve on y (row-major, K columns per row; K = 0: k at run time).
template <int K>
void simplicial_substitutions(const Eigen::SparseMatrix<double>& L, Eigen::Index k, double* y) {
  const Eigen::Index columns = K > 0 ? K : k;
  const int* start = L.outerIndexPtr();
  const int* row = L.innerIndexPtr();
  const double* value = L.valuePtr();
  const Eigen::Index n = L.cols();
  // Column j of L holds its diagonal first, then the rows below it (Eigen's simplicial layout).
  for (Eigen::Index j = 0; j < n; ++j) {
    double* yj = y + j * columns;
    for (Eigen::Index c = 0; c < columns; ++c) yj[c] /= value[start[j]];
    for (int p = start[j] + 1; p < start[j + 1]; ++p) {
      double* yi = y + static_cast<Eigen::Index>(row[p]) * columns;
      for (Eigen::Index c = 0; c < columns; ++c) yi[c] -= value[p] * yj[c];
    }
  }
  for (Eigen::Index j = n - 1; j >= 0; --j) {
    double* yj = y + j * columns;
    for (int p = start[j] + 1; p < start[j + 1]; ++p) {
      const double* yi = y + static_cast<Eigen::Index>(row[p]) * columns;
      for (Eigen::Index c = 0; c < columns; ++c) yj[c] -= value[p] * yi[c];
    }
    for (Eigen::Index c = 0; c < columns; ++c) yj[c] /= value[start[j]];
  }
}

// X = P^T L^-T L^-1 P B over the simplicial factor, B's k columns together (Eigen's solve walks L twice per
// column, with a permuted copy each way): y row-major n x k, so that each entry of L updates k adjacent
// values. Each column gets the same operations in the same order as a one-column solve.
Eigen::MatrixXd simplicial_solve(const SimplicialLlt& llt, const Eigen::MatrixXd& B) {
  const int* perm = llt.permutationP().indices().data(); // (P b)[perm[i]] = b[i]
  const Eigen::Index n = B.rows(), k = B.cols();
  Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> y(n, k);
  for (Eigen::Index i = 0; i < n; ++i) y.row(perm[i]) = B.row(i);
  const Eigen::SparseMatrix<double>& L = llt.matrixL().nestedExpression();
  if (k == 2)
    simplicial_substitutions<2>(L, k, y.data());
  else
    simplicial_substitutions<0>(L, k, y.data());
  Eigen::MatrixXd X(n, k);
  for (Eigen::Index i = 0; i < n; ++i) X.row(i) = y.row(perm[i]);
  return X;
}

void check_solve(FactorizationKind kind, Eigen::Index rows, const Eigen::MatrixXd& B) {
  if (kind == FactorizationKind::None)
    throw SolverError("sparse Cholesky: solve called before a factorization");
  if (B.rows() != rows)
    throw SolverError("sparse Cholesky: right-hand side has " + std::to_string(B.rows()) +
                      " rows, matrix has " + std::to_string(rows));
}
} // namespace

void SparseCholesky::solve(const Eigen::MatrixXd& B, Eigen::MatrixXd& X) {
  const FactorizationKind k = kind();
  check_solve(k, rows(), B);
  if (k == FactorizationKind::CholmodSupernodalLLT && impl_->supernodal) {
    impl_->supernodal->solve(B, X, thread_count(), impl_->supernodal_workspace);
    return;
  }
  solve_with_cholmod(B, X);
}

std::vector<int> SparseCholesky::gather_rows(const std::vector<int>& a_row) const {
  if (kind() != FactorizationKind::CholmodSupernodalLLT || !impl_->supernodal) return {};
  const auto n = static_cast<size_t>(rows());
  if (a_row.size() != n)
    throw SolverError("gather_rows: " + std::to_string(a_row.size()) + " rows for a factor of " +
                      std::to_string(n));
  std::vector<int> b_row(n, -1); // A's row -> B's row
  for (size_t r = 0; r < n; ++r) {
    const int a = a_row[r];
    if (a < 0 || static_cast<size_t>(a) >= n || b_row[static_cast<size_t>(a)] >= 0)
      throw SolverError("gather_rows: row " + std::to_string(r) + " names A's row " + std::to_string(a) +
                        ", out of range or named twice");
    b_row[static_cast<size_t>(a)] = static_cast<int>(r);
  }
  const auto* perm = static_cast<const int*>(impl_->llt->factor()->Perm);
  std::vector<int> gather(n);
  for (size_t i = 0; i < n; ++i) gather[i] = b_row[static_cast<size_t>(perm[i])];
  return gather;
}

void SparseCholesky::solve_gathered(const Eigen::MatrixXd& B, Eigen::MatrixXd& X,
                                    const std::vector<int>& gather) {
  const FactorizationKind k = kind();
  check_solve(k, rows(), B);
  if (k != FactorizationKind::CholmodSupernodalLLT || !impl_->supernodal ||
      gather.size() != static_cast<size_t>(rows()))
    throw SolverError("solve_gathered: needs CHOLMOD's supernodal factorization and a gather of its " +
                      std::to_string(rows()) + " rows (gather_rows)");
  impl_->supernodal->solve(B, X, thread_count(), impl_->supernodal_workspace, gather.data());
}

void SparseCholesky::solve_with_cholmod(const Eigen::MatrixXd& B, Eigen::MatrixXd& X) {
  const FactorizationKind k = kind();
  check_solve(k, rows(), B);
  if (k != FactorizationKind::CholmodSupernodalLLT) {
    X = solve(B);
    return;
  }
  Impl& impl = *impl_;
  impl.workspace.common = &impl.llt->cholmod();
  cholmod_solve_into(impl.llt->factor(), B, impl.workspace);
  const Eigen::Index n = B.rows(), columns = B.cols();
  X.resize(n, columns);
  const SolveWorkspace& ws = impl.workspace;
  for (Eigen::Index c = 0; c < columns; ++c)
    X.col(c) = Eigen::Map<const Eigen::VectorXd>(
        static_cast<const double*>(ws.X->x) + c * static_cast<Eigen::Index>(ws.X->d), n);
}

Eigen::MatrixXd SparseCholesky::solve(const Eigen::MatrixXd& B) const {
  const FactorizationKind k = kind();
  check_solve(k, rows(), B);
  if (k == FactorizationKind::Empty) return Eigen::MatrixXd(0, B.cols());
  if (k == FactorizationKind::SimplicialLDLT) return impl_->ldlt->solve(B);
  if (k == FactorizationKind::SimplicialLLT) return simplicial_solve(*impl_->simplicial, B);
  if (!impl_->supernodal) return impl_->llt->solve(B);
  Eigen::MatrixXd X;
  detail::SupernodalWorkspace ws; // a workspace of its own: const solves may run concurrently
  std::as_const(*impl_->supernodal).solve(B, X, thread_count(), ws);
  return X;
}

void SparseCholesky::release_solve_workspaces() {
  if (!impl_) return;
  impl_->workspace.release();
  impl_->supernodal_workspace = detail::SupernodalWorkspace();
}

FactorizationKind SparseCholesky::kind() const {
  return impl_ ? impl_->kind : FactorizationKind::None;
}

namespace {
std::size_t sparse_bytes(const Eigen::SparseMatrix<double>& A) {
  return static_cast<std::size_t>(A.nonZeros()) * (sizeof(double) + sizeof(int)) +
         static_cast<std::size_t>(A.outerSize() + 1) * sizeof(int);
}

// CHOLMOD's factor: its values, the supernodes' row indices, and the per-column and per-supernode arrays.
std::size_t cholmod_factor_bytes(const cholmod_factor* L) {
  const std::size_t index = L->itype == CHOLMOD_LONG ? sizeof(SuiteSparse_long) : sizeof(int);
  std::size_t bytes = L->xsize * sizeof(double) + 3 * L->n * index; // x; Perm, ColCount, IPerm
  if (L->is_super)
    bytes += L->ssize * index + 3 * (L->nsuper + 1) * index; // s; super, pi, px
  else
    bytes += L->nzmax * index + 4 * (L->n + 2) * index; // i; p, nz, next, prev
  return bytes;
}
} // namespace

std::size_t SparseCholesky::factor_bytes() const {
  if (!impl_) return 0;
  std::size_t bytes = 0;
  if (impl_->llt && impl_->llt->factor()) bytes += cholmod_factor_bytes(impl_->llt->factor());
  if (impl_->ldlt)
    bytes += sparse_bytes(impl_->ldlt->matrixL()) + impl_->ldlt->vectorD().size() * sizeof(double);
  if (impl_->simplicial) bytes += sparse_bytes(impl_->simplicial->matrixL());
  if (impl_->supernodal) bytes += impl_->supernodal->memory_bytes();
  return bytes;
}

std::size_t SparseCholesky::kept_matrix_bytes() const {
  return impl_ ? sparse_bytes(impl_->A) + sparse_bytes(impl_->analyzed) : 0;
}

Eigen::Index SparseCholesky::rows() const {
  return impl_ ? impl_->A.rows() : 0;
}

} // namespace iarap
