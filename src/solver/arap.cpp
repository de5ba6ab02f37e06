#include "iarap/solver/arap.h"

#include "iarap/core/errors.h"
#include "iarap/core/threads.h"
#include "iarap/mesh/connected_components.h"
#include "iarap/mesh/cotan.h"
#include "iarap/mesh/edge_topology.h"
#include "iarap/solver/arap_rhs.h"
#include "iarap/solver/fit_rotations.h"
#include "iarap/solver/system_pattern.h"

#include "../intrinsic/intrinsic_phases.h"
#include "local_global_loops.h"
#include "traced_elements.h"

#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <exception>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <system_error>
#include <thread>

namespace iarap {

namespace {

using Clock = std::chrono::steady_clock;

double ms_since(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

void check_positions(const Eigen::MatrixXd& U, Eigen::Index rows, const std::string& what) {
  if (U.rows() != rows || U.cols() != 3)
    throw InputError("ARAP: " + what + " must be " + std::to_string(rows) + " x 3, got " +
                     std::to_string(U.rows()) + " x " + std::to_string(U.cols()));
  for (Eigen::Index r = 0; r < rows; ++r)
    if (!U.row(r).allFinite())
      throw InputError("ARAP: " + what + " row " + std::to_string(r) + " is not finite");
}

} // namespace

ArapMethod parse_arap_method(const std::string& name) {
  if (name == "arap") return ArapMethod::Arap;
  if (name == "spokes-rims") return ArapMethod::SpokesRims;
  if (name == "iarap") return ArapMethod::Iarap;
  throw InputError("unknown ARAP method '" + name + "'; expected arap, spokes-rims or iarap");
}

std::string arap_method_name(ArapMethod method) {
  switch (method) {
  case ArapMethod::Arap:
    return "arap";
  case ArapMethod::SpokesRims:
    return "spokes-rims";
  case ArapMethod::Iarap:
    return "iarap";
  }
  return "unknown";
}

ArapAccelerator parse_arap_accelerator(const std::string& name) {
  if (name == "none") return ArapAccelerator::None;
  if (name == "anderson") return ArapAccelerator::Anderson;
  if (name == "lbfgs") return ArapAccelerator::Lbfgs;
  if (name == "newton") return ArapAccelerator::Newton;
  throw InputError("unknown ARAP accelerator '" + name + "'; expected anderson, lbfgs, newton or none");
}

std::string arap_accelerator_name(ArapAccelerator accelerator) {
  switch (accelerator) {
  case ArapAccelerator::None:
    return "none";
  case ArapAccelerator::Anderson:
    return "anderson";
  case ArapAccelerator::Lbfgs:
    return "lbfgs";
  case ArapAccelerator::Newton:
    return "newton";
  }
  return "none";
}

namespace {

// Which vertices are free and where the constrained ones go: [fixed; pinned].
struct ConstraintLayout {
  std::vector<int> constrained_slot; // #V position in [fixed; pinned], or -1 for a free vertex
  std::vector<int> constrained;      // the constrained vertices in slot order
  std::vector<int> pinned;
  std::vector<int> free;     // increasing
  Eigen::VectorXi free_slot; // #V position in free, or -1
};

ConstraintLayout constraint_layout(const ArapData& data, const Eigen::VectorXi& fixed) {
  const int n = static_cast<int>(data.V.rows());
  if (fixed.size() == 0) throw InputError("ARAP: the constrained (fixed) vertex set is empty");
  ConstraintLayout layout;
  layout.constrained_slot.assign(static_cast<size_t>(n), -1);
  std::vector<int>& slot = layout.constrained_slot;
  for (Eigen::Index k = 0; k < fixed.size(); ++k) {
    const int v = fixed(k);
    if (v < 0 || v >= n)
      throw InputError("ARAP: fixed[" + std::to_string(k) + "] = " + std::to_string(v) +
                       " is out of range; mesh has " + std::to_string(n) + " vertices");
    if (slot[v] >= 0)
      throw InputError("ARAP: fixed[" + std::to_string(k) + "] = " + std::to_string(v) + " repeats fixed[" +
                       std::to_string(slot[v]) + "]");
    slot[v] = static_cast<int>(k);
    layout.constrained.push_back(v);
  }

  // A component with no constrained vertex leaves L_ff singular (translations are free).
  std::vector<int> constrained_in(static_cast<size_t>(data.component_count), 0);
  std::vector<int> size_of(static_cast<size_t>(data.component_count), 0);
  std::vector<int> first_of(static_cast<size_t>(data.component_count), -1);
  for (int v = 0; v < n; ++v) {
    const int c = data.component(v);
    ++size_of[c];
    if (first_of[c] < 0) first_of[c] = v;
    if (slot[v] >= 0) ++constrained_in[c];
  }
  for (int c = 0; c < data.component_count; ++c) {
    if (constrained_in[c] > 0) continue;
    if (!data.pin_unconstrained_components)
      throw SolverError(
          "ARAP: connected component " + std::to_string(c) + " (" + std::to_string(size_of[c]) +
          " vertices, e.g. vertex " + std::to_string(first_of[c]) +
          ") has no constrained vertex, so the system is singular; constrain one of its vertices "
          "or enable pin_unconstrained_components");
    slot[first_of[c]] = static_cast<int>(layout.constrained.size());
    layout.constrained.push_back(first_of[c]);
    layout.pinned.push_back(first_of[c]);
  }

  layout.free_slot = Eigen::VectorXi::Constant(n, -1);
  layout.free.reserve(static_cast<size_t>(n));
  for (int v = 0; v < n; ++v)
    if (slot[v] < 0) {
      layout.free_slot(v) = static_cast<int>(layout.free.size());
      layout.free.push_back(v);
    }
  return layout;
}

// Calls emit(row, value) for column `column` of the symmetric L restricted to the free rows, renumbered
// (rows stay sorted because free_slot is increasing).
template <typename Emit>
void free_rows_of_column(const Eigen::SparseMatrix<double>& L, int column, const Eigen::VectorXi& free_slot,
                         Emit&& emit) {
  for (int k = L.outerIndexPtr()[column]; k < L.outerIndexPtr()[column + 1]; ++k) {
    const int row = free_slot(L.innerIndexPtr()[k]);
    if (row >= 0) emit(row, L.valuePtr()[k]);
  }
}

// L (#V x #V, symmetric, compressed) split into L_ff (free x free) and L_fc (free x constrained) directly
// in compressed form. Matrices with one pattern give L_ff with one pattern, which is what lets the
// symbolic factorization run on the pattern ahead of the values.
void split_system(const Eigen::SparseMatrix<double>& L, const ConstraintLayout& layout,
                  Eigen::SparseMatrix<double>& L_ff, Eigen::SparseMatrix<double>* L_fc) {
  auto build = [&](const std::vector<int>& columns, Eigen::SparseMatrix<double>& out) {
    const int nc = static_cast<int>(columns.size());
    out.resize(static_cast<Eigen::Index>(layout.free.size()), nc);
    int nnz = 0;
    for (int c = 0; c < nc; ++c)
      free_rows_of_column(L, columns[static_cast<size_t>(c)], layout.free_slot, [&](int, double) { ++nnz; });
    out.resizeNonZeros(nnz);
    int k = 0;
    out.outerIndexPtr()[0] = 0;
    for (int c = 0; c < nc; ++c) {
      free_rows_of_column(L, columns[static_cast<size_t>(c)], layout.free_slot, [&](int row, double value) {
        out.innerIndexPtr()[k] = row;
        out.valuePtr()[k++] = value;
      });
      out.outerIndexPtr()[c + 1] = k;
    }
  };
  build(layout.free, L_ff);
  if (L_fc) build(layout.constrained, *L_fc); // column j of symmetric L is row j: its free rows couple to j
}

void commit_layout(ArapData& data, const Eigen::VectorXi& fixed, ConstraintLayout& layout,
                   SparseCholesky& solver, Eigen::SparseMatrix<double>& L_fc) {
  data.solver = std::move(solver);
  data.L_fc = std::move(L_fc);
  data.fixed = fixed;
  data.pinned = Eigen::Map<const Eigen::VectorXi>(layout.pinned.data(),
                                                  static_cast<Eigen::Index>(layout.pinned.size()));
  data.free =
      Eigen::Map<const Eigen::VectorXi>(layout.free.data(), static_cast<Eigen::Index>(layout.free.size()));
  data.free_slot = std::move(layout.free_slot);
}

// Where run_beside runs side() while main() runs.
enum class Beside {
  // side() on the second thread of an OpenMP region of two (the pool's thread, already there and warm),
  // main() on the caller's. For the symbolic analysis beside the element build: a std::thread for it
  // started 1-2 ms after it was created and the build around it took 3-4 ms longer (beetle, original ARAP,
  // 2 threads: precompute 58-60 against 54-55 ms).
  SecondTeamThread,
  // side() on the caller's thread outside any OpenMP region, main() on a std::thread. For the numeric
  // factorization: CHOLMOD's supernodal factorization enters about 16,500 serialized OpenMP regions on
  // beetle, and inside an enclosing team libgomp allocates, initializes and frees a team for each one where
  // at the top level it reuses one (16,500 empty regions: 25 against 49 ms). On one thread of a region of
  // two it took 54-56 ms against 35-38 ms here (iARAP precompute, 2 threads: 70 -> 53 ms). On the caller's
  // thread
  // the factor is allocated from the caller's heap arena, which keeps the pages of what it freed (every
  // other thread gets an arena of its own: beetle, iARAP, 6600 against 5300 page faults per precompute).
  CallerOutsideOpenMP,
};

// Runs side() and main() at the same time when two threads are allowed, else one after the other; the
// first exception of either is rethrown after both have ended (main()'s first). side() is a serial CHOLMOD
// call (the symbolic analysis, the numeric factorization), main() what the precompute can do meanwhile.
// side() is allowed one thread (the setting of the thread that runs it): SparseCholesky then keeps CHOLMOD's
// own teams from crowding the cores main() is using (beetle's factorization beside the element finish: 29
// ms, 128 ms with CHOLMOD's teams). main()'s loops run on the cores side() leaves (CoreReservation;
// threads.h says why): one on a 2-core machine.
void run_beside(const std::function<void()>& side, const std::function<void()>& main, Beside where) {
  if (omp_get_max_threads() <= 1 || omp_in_parallel()) {
    side();
    main();
    return;
  }
  const int threads = omp_get_max_threads();
  std::exception_ptr side_error, main_error;
  auto run_side = [&] {
    const int saved = omp_get_max_threads();
    omp_set_num_threads(1);
    try {
      side();
    } catch (...) {
      side_error = std::current_exception();
    }
    omp_set_num_threads(saved);
  };
  auto run_main = [&] {
    try {
      main();
    } catch (...) {
      main_error = std::current_exception();
    }
  };
  bool beside = false; // false: the runtime gave one thread, or no thread could be made
  {
    const CoreReservation core;
    if (where == Beside::SecondTeamThread) {
      // main()'s loops may open nested teams on machines with more cores: allowed for the region's duration.
      const int active_levels = omp_get_max_active_levels();
      omp_set_max_active_levels(std::max(active_levels, 2));
#pragma omp parallel num_threads(2)
      {
        if (omp_get_num_threads() == 2) {
          if (omp_get_thread_num() == 0) {
            beside = true;
            run_main();
          } else {
            run_side();
          }
        }
      }
      omp_set_max_active_levels(active_levels);
    } else {
      std::thread helper;
      try {
        helper = std::thread([&] {
          omp_set_num_threads(
              threads); // a new thread starts from OpenMP's initial settings, not the caller's
          run_main();
        });
        beside = true;
      } catch (const std::system_error&) { // no thread to be had: one after the other, below
      }
      if (beside) {
        run_side();
        helper.join();
      }
    }
  }
  if (!beside) {
    side();
    main();
    return;
  }
  if (main_error) std::rethrow_exception(main_error);
  if (side_error) std::rethrow_exception(side_error);
}

} // namespace

namespace {

// iARAP's elements and its intrinsic summary from the traced triangulation (which is released).
void take_traced_elements(const Eigen::MatrixXd& V, std::optional<detail::TracedTriangulation>& traced,
                          ArapData& data) {
  data.elements = detail::traced_iarap_elements(V, traced->triangulation, traced->traces);
  const IntrinsicTriangulation& t = traced->triangulation;
  data.intrinsic = {t.flips,
                    t.non_delaunay_before,
                    t.non_delaunay_after,
                    t.mollify_delta,
                    t.E.rows(),
                    traced->traces.segment_count(),
                    t.obtuse_boundary_before,
                    t.obtuse_boundary_after,
                    t.inserted_t.size()};
  traced.reset();
}

} // namespace

ArapData arap_precompute(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, const Eigen::VectorXi& fixed,
                         const ArapOptions& options) {
  check_arap_mesh(V, F);
  ArapData data;
  data.method = options.method;
  data.pin_unconstrained_components = options.pin_unconstrained_components;
  data.V = V;
  data.F = F;
  data.component = vertex_components(F, static_cast<int>(V.rows()), &data.component_count);
  ConstraintLayout layout = constraint_layout(data, fixed); // bad constraints fail before any heavy work
  const int n = static_cast<int>(V.rows());

  // The pattern of L (hence of L_ff) follows from F alone, so the pattern and CHOLMOD's symbolic analysis are
  // built beside the elements (for iARAP: beside the intrinsic flips); with one thread, first. The edge
  // topology and the face cotangents are computed once and passed to whatever needs them.
  SystemPattern pattern;
  Eigen::SparseMatrix<double> L_ff, L_fc;
  SparseCholesky solver;
  double analyze_ms = 0.0;
  auto build_pattern = [&](const EdgeTopology& topology) { pattern = system_pattern(F, n, topology); };
  auto analyze = [&] {
    split_system(pattern.matrix, layout, L_ff, nullptr);
    const auto t = Clock::now();
    solver.analyze(L_ff);
    analyze_ms = ms_since(t);
  };

  if (options.method != ArapMethod::Iarap) {
    const EdgeTopology topology = edge_topology(F, n);
    double build_ms = 0.0;
    auto start = Clock::now();
    run_beside(
        [&] {
          build_pattern(topology);
          analyze();
        },
        [&] {
          const auto t = Clock::now();
          const Eigen::MatrixXd C = face_cotangents(V, F);
          data.elements = options.method == ArapMethod::Arap ? arap_edge_elements(V, topology, C)
                                                             : spokes_rims_elements(V, F, C);
          build_ms = ms_since(t);
        },
        Beside::SecondTeamThread);
    // What the build did not hide of the analysis counts as factorization time.
    data.timings.factor_ms = std::max(0.0, ms_since(start) - build_ms);
    data.timings.assembly_ms = build_ms;
    start = Clock::now();
    data.L = element_system_matrix(data.elements, F, pattern);
    data.timings.assembly_ms += ms_since(start);
    start = Clock::now();
    split_system(data.L, layout, L_ff, &L_fc);
    solver.factorize(L_ff); // throws SolverError
    data.timings.factor_ms += ms_since(start);
  } else {
    // iARAP's L = 2 B^T D_w B is twice the cotan Laplacian of the input (cotan_system_matrix), so its
    // assembly, analysis and numeric factorization need nothing of the intrinsic triangulation: they run on
    // the caller's thread (its heap arena keeps the factor's pages warm) while the flips, the tracing and the
    // elements are built beside them. Where the intrinsic lengths are not the input's (mollified degenerate
    // faces) the identity does not hold: L is then assembled from the elements and factorized after them.
    // The edge topology and the input's face cotangents and corner angles are computed once, for both: the
    // pattern and the cotan Laplacian read the first two, the signpost triangulation takes all three. Each
    // drops its references when done with them.
    std::optional<detail::TracedTriangulation> traced;
    double intrinsic_ms = 0.0, elements_ms = 0.0, cotan_ms = 0.0;
    bool cotan_factorized = false;
    auto start = Clock::now();
    detail::SignpostInput input = detail::signpost_input(V, F, options.intrinsic.refine_boundary);
    const double input_ms = ms_since(start);
    std::shared_ptr<const EdgeTopology> topology = input.topology;
    std::shared_ptr<const Eigen::MatrixXd> C = input.C;
    run_beside(
        [&] {
          build_pattern(*topology);
          topology.reset();
          analyze();
          const auto t = Clock::now();
          if (!C->allFinite()) return; // degenerate faces: mollified lengths, the identity does not hold
          data.L = cotan_system_matrix(F, *C, pattern);
          C.reset();
          split_system(data.L, layout, L_ff, &L_fc);
          cotan_ms = ms_since(t);
          solver.factorize(L_ff); // throws SolverError
          cotan_factorized = true;
        },
        [&] {
          auto t = Clock::now();
          traced = detail::trace_phase(detail::flip_phase(V, F, options.intrinsic, &input), false);
          intrinsic_ms = input_ms + ms_since(t);
          t = Clock::now();
          take_traced_elements(V, traced, data);
          detail::finish_elements(V, data.elements, true);
          elements_ms = ms_since(t);
        },
        Beside::CallerOutsideOpenMP);
    data.timings.intrinsic_ms = intrinsic_ms;
    data.timings.assembly_ms = elements_ms + cotan_ms;
    // What the intrinsic and element build did not hide of the analysis and factorization.
    data.timings.factor_ms = std::max(0.0, ms_since(start) - intrinsic_ms - elements_ms - cotan_ms);
    if (!cotan_factorized || data.intrinsic.mollify_delta != 0.0) {
      start = Clock::now();
      data.L = element_system_matrix(data.elements, F, pattern);
      data.timings.assembly_ms += ms_since(start);
      start = Clock::now();
      split_system(data.L, layout, L_ff, &L_fc);
      solver.factorize(L_ff);
      data.timings.factor_ms += ms_since(start);
    }
  }
  data.timings.analyze_ms = analyze_ms;
  data.R.assign(static_cast<size_t>(data.elements.num_cells), Eigen::Matrix3d::Identity());
  commit_layout(data, fixed, layout, solver, L_fc);
  return data;
}

void arap_set_fixed(ArapData& data, const Eigen::VectorXi& fixed) {
  const auto start = Clock::now();
  ConstraintLayout layout = constraint_layout(data, fixed);
  Eigen::SparseMatrix<double> L_ff, L_fc;
  split_system(data.L, layout, L_ff, &L_fc);
  SparseCholesky solver(L_ff); // throws SolverError; data is untouched until here
  commit_layout(data, fixed, layout, solver, L_fc);
  data.timings.analyze_ms = 0.0; // inside factor_ms here
  data.timings.factor_ms = ms_since(start);
}

ArapReport arap_solve(ArapData& data, const Eigen::MatrixXd& targets, Eigen::MatrixXd& U,
                      const ArapSolveOptions& options) {
  const auto start = Clock::now();
  if (options.max_iterations < 0)
    throw InputError("ARAP: max_iterations must be >= 0, got " + std::to_string(options.max_iterations));
  if (std::isnan(options.tolerance)) throw InputError("ARAP: tolerance is NaN");
  if (!(options.gradient_tolerance >= 0))
    throw InputError("ARAP: gradient_tolerance must be >= 0, got " +
                     std::to_string(options.gradient_tolerance));
  if (options.window < 0)
    throw InputError("ARAP: window must be >= 0, got " + std::to_string(options.window));
  check_positions(targets, data.fixed.size(), "targets");
  check_positions(U, data.V.rows(), "initial guess U");
  detail::LocalGlobalProblem problem(data, targets, U);
  return detail::run_local_global(problem, options, data.solver.kind(), start);
}

double arap_energy(const ArapData& data, const Eigen::MatrixXd& U) {
  return arap_cell_energy(data, U).sum();
}

Eigen::VectorXd arap_cell_energy(const ArapData& data, const Eigen::MatrixXd& U) {
  check_positions(U, data.V.rows(), "positions U");
  ArapElements::ValueRows U_rows;
  std::vector<Eigen::Matrix3d> R;
  Eigen::VectorXd cell_energy;
  fit_rotations(data.elements, U, U_rows, R, cell_energy);
  return cell_energy;
}

Eigen::MatrixXd arap_gradient(const ArapData& data, const Eigen::MatrixXd& U) {
  check_positions(U, data.V.rows(), "positions U");
  ArapElements::ValueRows U_rows;
  std::vector<Eigen::Matrix3d> R;
  Eigen::VectorXd cell_energy;
  Eigen::MatrixXd rhs;
  fit_rotations(data.elements, U, U_rows, R, cell_energy);
  arap_rhs(data.elements, R, rhs);
  return data.L * U - rhs; // Eq. 14
}

const std::vector<Eigen::Matrix3d>& arap_rotations(const ArapData& data) {
  return data.R;
}

const Eigen::SparseMatrix<double>& arap_system_matrix(const ArapData& data) {
  return data.L;
}

FactorizationKind arap_factorization(const ArapData& data) {
  return data.solver.kind();
}

} // namespace iarap
