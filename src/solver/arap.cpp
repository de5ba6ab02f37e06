#include "iarap/solver/arap.h"

#include "iarap/core/errors.h"
#include "iarap/core/resident_memory.h"
#include "iarap/core/stopwatch.h"
#include "iarap/mesh/connected_components.h"
#include "iarap/mesh/cotan.h"
#include "iarap/mesh/edge_topology.h"
#include "iarap/solver/arap_rhs.h"
#include "iarap/solver/fit_rotations.h"
#include "iarap/solver/system_pattern.h"

#include "../core/run_beside.h"
#include "../intrinsic/intrinsic_phases.h"
#include "cell_stiffness.h"
#include "constraint_layout.h"
#include "cover_elements.h"
#include "local_global_loops.h"
#include "local_global_problem.h"
#include "quadratic_terms.h"
#include "rigid_group_problem.h"
#include "rigid_groups.h"
#include "soft_terms.h"
#include "traced_elements.h"

#include <algorithm>
#include <cmath>
#include <exception>
#include <memory>
#include <optional>
#include <string>

namespace iarap {

namespace {

// Checks X: rows x 3, or for planar data rows x 2 or rows x 3 in the plane z = 0; finite.
void check_solver_positions(const ArapData& data, const Eigen::MatrixXd& X, Eigen::Index rows,
                            const std::string& what) {
  const bool two_columns = data.planar && X.cols() == 2;
  const Eigen::Index cols = two_columns ? 2 : 3;
  if (X.rows() != rows || X.cols() != cols)
    throw InputError("ARAP: " + what + " must be " + std::to_string(rows) + " x " + std::to_string(cols) +
                     (two_columns ? " (planar)" : "") + ", got " + std::to_string(X.rows()) + " x " +
                     std::to_string(X.cols()));
  for (Eigen::Index r = 0; r < rows; ++r)
    if (!X.row(r).allFinite())
      throw InputError("ARAP: " + what + " row " + std::to_string(r) + " is not finite");
  if (!data.planar || two_columns) return;
  for (Eigen::Index r = 0; r < rows; ++r)
    if (X(r, 2) != 0.0)
      throw InputError("ARAP: " + what + " row " + std::to_string(r) + " has z = " + std::to_string(X(r, 2)) +
                       "; a planar ARAP deforms in the plane z = 0 (give #rows x 2 positions, or precompute "
                       "without ArapOptions::planar for a 3D deformation)");
}

// A rows x 2 X as rows x 3 at z = 0.
Eigen::MatrixXd embedded(const Eigen::MatrixXd& X) {
  Eigen::MatrixXd X3(X.rows(), 3);
  X3.leftCols(2) = X;
  X3.col(2).setZero();
  return X3;
}

// The system of the global step as arap_precompute builds it. The pattern of L (hence of L_ff) follows from F
// alone, so the pattern and CHOLMOD's symbolic analysis are built beside the elements (for iARAP: beside the
// intrinsic flips); with one thread, first. The values and the numeric factorization follow once L is known.
struct SystemBuild {
  SystemPattern pattern;
  Eigen::SparseMatrix<double> Q; // the soft constraints' part (0 x 0 without): L_ff and L_fc are of L + Q
  Eigen::SparseMatrix<double> L_ff, L_fc;
  SparseCholesky solver;
  double analyze_ms = 0;
  bool factorized = false;
};

// Frees A's arrays: Eigen 3.4's SparseMatrix has no move assignment, and assigning it an empty matrix keeps
// its capacity.
void free_sparse(Eigen::SparseMatrix<double>& A) {
  Eigen::SparseMatrix<double>().swap(A);
}

// The pattern's arrays, freed (as free_sparse).
void free_pattern(SystemPattern& pattern) {
  free_sparse(pattern.matrix);
  pattern.face_slot.resize(0, 9);
}

// CHOLMOD's symbolic analysis of L_ff on the pattern.
void analyze(const detail::ConstraintLayout& layout, SystemBuild& system) {
  detail::split_system(system.pattern.matrix, layout, system.L_ff, nullptr);
  timed(system.analyze_ms, [&] { system.solver.analyze(system.L_ff); });
  free_sparse(system.L_ff); // the analysis keeps its own copy of the pattern
}

// L_ff and L_fc from L, and the numeric factorization of L_ff (throws SolverError).
void factorize(const Eigen::SparseMatrix<double>& L, const detail::ConstraintLayout& layout,
               SystemBuild& system) {
  detail::split_system(detail::with_soft(L, system.Q), layout, system.L_ff, &system.L_fc);
  system.solver.factorize(system.L_ff);
  free_sparse(system.L_ff); // the solver keeps its own copy for refactorization
  system.factorized = true;
}

// The rest mesh as the builders take it, #V x 3: a #V x 2 V embedded at z = 0; a planar #V x 3 one must lie
// in that plane (InputError naming the first vertex off it).
Eigen::MatrixXd rest_positions(const Eigen::MatrixXd& V, bool planar) {
  if (V.cols() == 2) return embedded(V);
  if (planar && V.cols() == 3)
    for (Eigen::Index v = 0; v < V.rows(); ++v)
      if (V(v, 2) != 0.0)
        throw InputError("ARAP: vertex " + std::to_string(v) + " has z = " + std::to_string(V(v, 2)) +
                         "; ArapOptions::planar needs a mesh in the plane z = 0");
  return V;
}

// data.min_weight and data.negative_weights from the elements' weights (before they are released).
void summarize_weights(ArapData& data) {
  const Eigen::VectorXd& w = data.elements.w;
  data.min_weight = w.size() > 0 ? w.minCoeff() : 0.0;
  data.negative_weights = (w.array() < 0.0).count();
}

// What arap_precompute knows before any element: the rest mesh, the method and the connected components.
ArapData rest_data(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, const ArapOptions& options) {
  ArapData data;
  data.method = options.method;
  data.pin_unconstrained_components = options.pin_unconstrained_components;
  data.V = V;
  data.F = F;
  data.component = vertex_components(F, static_cast<int>(V.rows()), &data.component_count);
  return data;
}

// Original ARAP and spokes-and-rims: the elements from the input's edges or faces and their cotangents,
// built beside the pattern and its analysis. The edge topology is computed once, for both.
void build_cotan_elements(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, ArapMethod method,
                          const detail::ConstraintLayout& layout, ArapData& data, SystemBuild& system) {
  const EdgeTopology topology = edge_topology(F, static_cast<int>(V.rows()));
  double build_ms = 0.0;
  const auto start = Clock::now();
  detail::run_beside(
      [&] {
        system.pattern = system_pattern(F, static_cast<int>(V.rows()), topology);
        analyze(layout, system);
      },
      [&] {
        timed(build_ms, [&] {
          const Eigen::MatrixXd C = face_cotangents(V, F);
          data.elements =
              method == ArapMethod::Arap ? arap_edge_elements(V, topology, C) : spokes_rims_elements(V, F, C);
        });
      },
      detail::Beside::SecondTeamThread);
  // What the build did not hide of the analysis counts as factorization time.
  data.timings.factor_ms = std::max(0.0, ms_since(start) - build_ms);
  data.timings.assembly_ms = build_ms;
}

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

// iARAP on input that is not an oriented manifold (or with IntrinsicOptions::tufted_cover): the intrinsic
// Delaunay triangulation of the tufted cover (src/intrinsic/tufted_cover.h), its traced edges and the
// elements on them, folded back to the input's vertices (fold_cover_elements); the pattern of L and its
// analysis run beside. L is assembled from the elements afterwards (system.factorized stays false).
// `analyzed`: the analysis ran already (beside the manifold check, build_intrinsic_elements).
void build_tufted_elements(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, const EdgeTopology& topology,
                           const IntrinsicOptions& intrinsic, const detail::ConstraintLayout& layout,
                           ArapData& data, SystemBuild& system, bool analyzed = false) {
  double intrinsic_ms = 0.0, elements_ms = 0.0;
  const auto start = Clock::now();
  const int n = static_cast<int>(V.rows());
  detail::run_beside(
      [&] {
        if (analyzed) return;
        system.pattern = system_pattern(F, n, topology);
        analyze(layout, system);
      },
      [&] {
        std::optional<detail::TracedTriangulation> traced;
        const detail::TuftedCover cover = timed(intrinsic_ms, [&] {
          detail::TuftedCover c = detail::tufted_cover(V, F, topology);
          traced = detail::trace_phase(detail::flip_cover_phase(c, intrinsic), false);
          return c;
        });
        timed(elements_ms, [&] {
          take_traced_elements(cover.V, traced, data);
          detail::fold_cover_elements(data.elements, cover.vertex, n);
          detail::finish_elements(V, data.elements, true);
        });
        data.intrinsic.tufted_cover = true;
        data.intrinsic.cover_vertices = cover.vertex.size();
      },
      detail::Beside::SecondTeamThread);
  data.timings.intrinsic_ms = intrinsic_ms;
  data.timings.assembly_ms = elements_ms;
  data.timings.factor_ms = std::max(0.0, ms_since(start) - intrinsic_ms - elements_ms);
}

// iARAP: the intrinsic Delaunay triangulation, its traced edges and the elements on them (Eq. 9, 11).
// Its L = 2 B^T D_w B is twice the cotan Laplacian of the input (cotan_system_matrix), so its assembly,
// analysis and numeric factorization need nothing of the intrinsic triangulation: they run on the caller's
// thread (its heap arena keeps the factor's pages warm) while the flips, the tracing and the elements are
// built beside them. Where the intrinsic lengths are not the input's (mollified degenerate faces) the
// identity does not hold: system.factorized is then false, and L is assembled from the elements. The edge
// topology and the input's face cotangents and corner angles are computed once (signpost_input) for both:
// the pattern and the cotan Laplacian read the first two, the signpost triangulation all three; each drops
// its references when done with them.
// release_elements: nothing after the precompute reads the element arrays (ArapOptions::keep_elements,
// rigid groups); where L then needs none of them either, the streamed layout's build releases them.
void build_intrinsic_elements(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F,
                              const IntrinsicOptions& intrinsic, bool cotan_identity, bool release_elements,
                              const detail::ConstraintLayout& layout, ArapData& data, SystemBuild& system) {
  std::optional<detail::TracedTriangulation> traced;
  double intrinsic_ms = 0.0, elements_ms = 0.0, cotan_ms = 0.0;
  const auto start = Clock::now();
  detail::SignpostInput input =
      timed(intrinsic_ms, [&] { return detail::signpost_input(V, F, intrinsic.refine_boundary); });
  trace_resident("signpost input");
  if (intrinsic.tufted_cover)
    return build_tufted_elements(V, F, *input.topology, intrinsic, layout, data, system);
  std::shared_ptr<const EdgeTopology> topology = input.topology;
  std::shared_ptr<const Eigen::MatrixXd> C = input.C;
  bool manifold = true;
  std::exception_ptr cotan_error;
  detail::run_beside(
      [&] {
        system.pattern = system_pattern(F, static_cast<int>(V.rows()), *topology);
        topology.reset();
        trace_resident("pattern");
        analyze(layout, system);
        release_free_heap(V.rows()); // the ordering's workspaces
        trace_resident("analyzed");
        // Degenerate faces (mollified lengths) or stiffness: the identity does not hold.
        if (!cotan_identity || !C->allFinite()) return;
        // A failure counts only for a manifold (below): the tufted cover's L is another matrix.
        try {
          data.L = timed(cotan_ms, [&] { return cotan_system_matrix(F, *C, system.pattern); });
          C.reset();
          trace_resident("cotan matrix");
          // The pattern (its face slots alone are 36 bytes per face) is not needed again unless the
          // intrinsic build mollified lengths; factorize_element_system rebuilds it then.
          free_pattern(system.pattern);
          factorize(data.L, layout, system);
        } catch (const std::exception&) {
          cotan_error = std::current_exception();
        }
        release_free_heap(V.rows()); // CHOLMOD's permuted copies and update matrices
        trace_resident("factorized");
      },
      [&] {
        // Input that is not an oriented manifold takes the tufted cover (docs/nonmanifold.md), below. The
        // check runs here, beside the analysis, which serves either build (2.77M vertices: 1.0 s).
        manifold = timed(intrinsic_ms, [&] {
          return detail::is_oriented_manifold(F, *input.topology, static_cast<int>(V.rows()));
        });
        trace_resident("manifold checked");
        if (!manifold) return;
        timed(intrinsic_ms,
              [&] { traced = detail::trace_phase(detail::flip_phase(V, F, intrinsic, &input), false); });
        trace_resident("traced");
        timed(elements_ms, [&] {
          take_traced_elements(V, traced, data);
          release_free_heap(V.rows()); // the intrinsic triangulation and its traces
          trace_resident("elements");
          summarize_weights(data);
          detail::finish_elements(V, data.elements, true,
                                  release_elements && cotan_identity && data.intrinsic.mollify_delta == 0.0);
          release_free_heap(V.rows()); // the element arrays and the layout's workspaces
        });
      },
      detail::Beside::CallerOutsideOpenMP);
  if (!manifold) {
    // The cotan factorization beside (if any) was of the input's cotan Laplacian; the tufted cover's L comes
    // from its elements, on the same pattern (a numeric refactorization).
    system.factorized = false;
    // intrinsic_ms so far: the signpost input and the manifold check.
    const double input_and_check_ms = intrinsic_ms, beside_ms = ms_since(start);
    build_tufted_elements(V, F, *input.topology, intrinsic, layout, data, system, true);
    data.timings.intrinsic_ms += input_and_check_ms;
    data.timings.factor_ms += std::max(0.0, beside_ms - input_and_check_ms); // the analysis they did not hide
    return;
  }
  if (cotan_error) std::rethrow_exception(cotan_error);
  data.timings.intrinsic_ms = intrinsic_ms;
  data.timings.assembly_ms = elements_ms + cotan_ms;
  // What the intrinsic and element build did not hide of the analysis and factorization.
  data.timings.factor_ms = std::max(0.0, ms_since(start) - intrinsic_ms - elements_ms - cotan_ms);
  if (data.intrinsic.mollify_delta != 0.0 || !cotan_identity) system.factorized = false;
}

// L from the elements (Eq. 17) and its factorization, where the element build did not factorize it.
void factorize_element_system(const Eigen::MatrixXi& F, const detail::ConstraintLayout& layout,
                              ArapData& data, SystemBuild& system) {
  data.L = timed(data.timings.assembly_ms, [&] {
    if (system.pattern.matrix.size() == 0)
      system.pattern = system_pattern(F, static_cast<int>(data.V.rows()));
    return element_system_matrix(data.elements, F, system.pattern);
  });
  timed(data.timings.factor_ms, [&] { factorize(data.L, layout, system); });
}

} // namespace

void check_arap_stiffness(const Eigen::VectorXd& s, Eigen::Index n) {
  if (s.size() != n)
    throw InputError("ARAP: stiffness has " + std::to_string(s.size()) + " entries for a mesh of " +
                     std::to_string(n) + " vertices");
  for (Eigen::Index v = 0; v < n; ++v)
    if (!(std::isfinite(s(v)) && s(v) > 0))
      throw InputError("ARAP: stiffness of vertex " + std::to_string(v) + " is " + std::to_string(s(v)) +
                       "; it must be finite and > 0");
}

ArapData arap_precompute(const Eigen::MatrixXd& V_in, const Eigen::MatrixXi& F, const Eigen::VectorXi& fixed,
                         const ArapOptions& options) {
  return arap_precompute(V_in, F, fixed, ArapSoftConstraints{}, options);
}

ArapData arap_precompute(const Eigen::MatrixXd& V_in, const Eigen::MatrixXi& F, const Eigen::VectorXi& fixed,
                         const ArapSoftConstraints& soft, const ArapOptions& options) {
  // What the caller freed before (a subdivision's transients, say) goes back to the system first: the
  // precompute's threads allocate from heaps of their own, which could not reuse it. Small meshes skip
  // it: there the freed heap is what the next precompute reuses without page faults (malloc_settings.cpp).
  release_free_heap(V_in.rows());
  trace_resident("precompute start");
  const Eigen::MatrixXd V = rest_positions(V_in, options.planar);
  check_arap_mesh(V, F);
  ArapData data = rest_data(V, F, options);
  data.planar = options.planar || V_in.cols() == 2;
  // Bad constraints fail before any heavy work.
  detail::check_soft_constraints(soft, static_cast<int>(V.rows()), F, fixed);
  if (options.stiffness.size() > 0) check_arap_stiffness(options.stiffness, V.rows());
  check_rigid_groups(options.rigid_groups, V.rows());
  const bool stiffness = !detail::is_unit_stiffness(options.stiffness);
  detail::ConstraintLayout layout = detail::constraint_layout(data, fixed, soft);
  SystemBuild system;
  system.solver.set_ordering(options.ordering);
  system.Q = detail::soft_system_matrix(detail::soft_points(soft, F), static_cast<int>(V.rows()));
  // Nothing after the precompute reads the element arrays but the rigid groups' system (and callers that
  // ask for them): they are released, during the streamed layout's build where nothing later needs them.
  const bool release_elements = !options.keep_elements && options.rigid_groups.empty();
  if (options.method == ArapMethod::Iarap)
    build_intrinsic_elements(V, F, options.intrinsic, !stiffness, release_elements, layout, data, system);
  else
    build_cotan_elements(V, F, options.method, layout, data, system);
  if (stiffness)
    detail::apply_cell_stiffness(data.elements, detail::cell_stiffness_of(data.elements, options.stiffness));
  if (!system.factorized) factorize_element_system(F, layout, data, system);
  data.elements.planar = data.planar;
  if (!data.elements.arrays_released) summarize_weights(data);
  data.timings.analyze_ms = system.analyze_ms;
  data.R.assign(static_cast<size_t>(data.elements.num_cells), Eigen::Matrix3d::Identity());
  if (!options.rigid_groups.empty())
    data.rigid = detail::rigid_group_system(options.rigid_groups, data, system.Q, soft, fixed, layout);
  detail::commit_layout(data, fixed, layout, system.solver, system.L_fc);
  data.soft = soft;
  data.Q.swap(system.Q);
  if (release_elements && !data.elements.arrays_released) release_element_arrays(data.elements);
  free_pattern(system.pattern);
  free_sparse(system.L_fc);
  // What the precompute freed goes back to the system: the resident set is then what data holds.
  release_free_heap(V.rows());
  trace_resident("precomputed");
  return data;
}

void arap_set_fixed(ArapData& data, const Eigen::VectorXi& fixed) {
  const auto start = Clock::now();
  detail::check_soft_constraints(data.soft, static_cast<int>(data.V.rows()), data.F, fixed);
  detail::ConstraintLayout layout = detail::constraint_layout(data, fixed, data.soft);
  Eigen::SparseMatrix<double> L_ff, L_fc;
  detail::split_system(detail::with_soft(data.L, data.Q), layout, L_ff, &L_fc);
  SparseCholesky solver;
  solver.set_ordering(data.solver.ordering());
  solver.factorize(L_ff); // throws SolverError; data is untouched until here
  RigidGroupSystem rigid = data.rigid.empty() ? RigidGroupSystem()
                                              : detail::rigid_group_system(data.rigid.groups, data, data.Q,
                                                                           data.soft, fixed, layout);
  detail::commit_layout(data, fixed, layout, solver, L_fc);
  data.rigid = std::move(rigid);
  data.timings.analyze_ms = 0.0; // inside factor_ms here
  data.timings.factor_ms = ms_since(start);
}

void arap_set_soft_weights(ArapData& data, const Eigen::VectorXd& vertex_weights,
                           const Eigen::VectorXd& face_weights) {
  const auto start = Clock::now();
  ArapSoftConstraints soft = data.soft;
  soft.vertex_weights = vertex_weights;
  soft.face_weights = face_weights;
  detail::check_soft_constraints(soft, static_cast<int>(data.V.rows()), data.F, data.fixed);
  detail::ConstraintLayout layout = detail::constraint_layout(data, data.fixed, soft);
  Eigen::SparseMatrix<double> Q =
      detail::soft_system_matrix(detail::soft_points(soft, data.F), static_cast<int>(data.V.rows()));
  Eigen::SparseMatrix<double> L_ff, L_fc;
  detail::split_system(detail::with_soft(data.L, Q), layout, L_ff, &L_fc);
  // Q lies in L's pattern, so L_ff keeps the factorized pattern: factorize reuses the symbolic analysis.
  data.solver.factorize(L_ff); // throws SolverError (data.solver is then empty)
  if (!data.rigid.empty())
    data.rigid = detail::rigid_group_system(data.rigid.groups, data, Q, soft, data.fixed, layout);
  data.L_fc = std::move(L_fc);
  data.soft = std::move(soft);
  data.Q = std::move(Q);
  data.free_rows.reset(); // of the old L + Q
  data.timings.analyze_ms = 0.0;
  data.timings.factor_ms = ms_since(start);
}

namespace {

// Rotation smoothing couples the cells' rotations and the groups' turns would join that coupled local step:
// not built yet.
void check_rigid_solve_options(const ArapSolveOptions& options) {
  if (options.rotation_smoothing != 0.0)
    throw InputError("ARAP: rotation smoothing is not supported with rigid groups (give one or the other)");
}

ArapReport solve_checked(ArapData& data, const Eigen::MatrixXd& targets, const Eigen::MatrixXd& soft_targets,
                         const Eigen::MatrixXd& forces, Eigen::MatrixXd& U, const ArapSolveOptions& options,
                         Clock::time_point start) {
  ArapReport report;
  if (!data.rigid.empty()) {
    check_rigid_solve_options(options);
    detail::RigidGroupProblem problem(data, targets, U, soft_targets, forces);
    report = detail::run_local_global(problem, options, data.rigid.solver.kind(), start);
  } else {
    detail::LocalGlobalProblem problem(data, targets, U, soft_targets, forces, options.rotation_smoothing,
                                       options.warm_start_rotations);
    report = detail::run_local_global(problem, options, data.solver.kind(), start);
  } // U holds the result in the file's order from here
  // The terms' energies at the result, in the file's order.
  const ArapElements::ValueRows U_rows = U;
  for (const auto& term : detail::quadratic_terms(data, soft_targets, forces, nullptr))
    (term->kind() == detail::QuadraticTerm::Kind::Penalty ? report.penalty : report.potential) =
        term->energy(U_rows);
  report.arap_energy = (report.energies.empty() ? report.initial_energy : report.energies.back()) -
                       report.penalty - report.potential;
  return report;
}

} // namespace

ArapReport arap_solve(ArapData& data, const Eigen::MatrixXd& targets, Eigen::MatrixXd& U,
                      const ArapSolveOptions& options) {
  if (data.soft.size() != 0)
    throw InputError("ARAP: the data has " + std::to_string(data.soft.size()) +
                     " soft constraints; give their targets (arap_solve with soft_targets)");
  return arap_solve(data, targets, Eigen::MatrixXd(0, 3), U, options);
}

ArapReport arap_solve(ArapData& data, const Eigen::MatrixXd& targets, const Eigen::MatrixXd& soft_targets,
                      Eigen::MatrixXd& U, const ArapSolveOptions& options) {
  const auto start = Clock::now();
  detail::check_solve_options_and_state(options);
  check_solver_positions(data, targets, data.fixed.size(), "targets");
  check_solver_positions(data, soft_targets, data.soft.size(), "soft targets");
  check_solver_positions(data, U, data.V.rows(), "initial guess U");
  if (options.forces.size() > 0) check_solver_positions(data, options.forces, data.V.rows(), "forces");
  const Eigen::MatrixXd target_rows = targets.cols() == 2 ? embedded(targets) : targets;
  const Eigen::MatrixXd soft_rows = soft_targets.cols() == 2 ? embedded(soft_targets) : soft_targets;
  const Eigen::MatrixXd force_rows = options.forces.cols() == 2 ? embedded(options.forces) : options.forces;
  if (U.cols() == 2) { // planar: solved embedded at z = 0, handed back in the caller's two columns
    Eigen::MatrixXd U3 = embedded(U);
    ArapReport report = solve_checked(data, target_rows, soft_rows, force_rows, U3, options, start);
    U = U3.leftCols(2);
    return report;
  }
  return solve_checked(data, target_rows, soft_rows, force_rows, U, options, start);
}

double arap_penalty(const ArapData& data, const Eigen::MatrixXd& soft_targets, const Eigen::MatrixXd& U) {
  check_solver_positions(data, soft_targets, data.soft.size(), "soft targets");
  check_solver_positions(data, U, data.V.rows(), "positions U");
  if (data.soft.size() == 0) return 0.0;
  const detail::SoftPointTerm penalty(data, soft_targets.cols() == 2 ? embedded(soft_targets) : soft_targets,
                                      nullptr);
  return penalty.energy(U.cols() == 2 ? embedded(U) : U);
}

Eigen::MatrixXd arap_penalty_gradient(const ArapData& data, const Eigen::MatrixXd& soft_targets,
                                      const Eigen::MatrixXd& U) {
  check_solver_positions(data, soft_targets, data.soft.size(), "soft targets");
  check_solver_positions(data, U, data.V.rows(), "positions U");
  const Eigen::MatrixXd T = soft_targets.cols() == 2 ? embedded(soft_targets) : soft_targets;
  const Eigen::MatrixXd X = U.cols() == 2 ? embedded(U) : U;
  Eigen::MatrixXd G = Eigen::MatrixXd::Zero(X.rows(), 3);
  const std::vector<detail::SoftPoint> points = detail::soft_points(data.soft, data.F);
  for (size_t k = 0; k < static_cast<size_t>(data.soft.soft_size()); ++k) { // 2 W c (c^T U - t)
    const detail::SoftPoint& p = points[k];
    Eigen::RowVector3d d = -T.row(static_cast<Eigen::Index>(k));
    for (int j = 0; j < 3; ++j) d += p.c[j] * X.row(p.v[j]);
    for (int j = 0; j < 3; ++j) G.row(p.v[j]) += 2.0 * p.W * p.c[j] * d;
  }
  return U.cols() == 2 ? Eigen::MatrixXd(G.leftCols(2)) : G;
}

double arap_energy(const ArapData& data, const Eigen::MatrixXd& U) {
  return arap_cell_energy(data, U).sum();
}

Eigen::VectorXd arap_cell_energy(const ArapData& data, const Eigen::MatrixXd& U) {
  check_solver_positions(data, U, data.V.rows(), "positions U");
  if (U.cols() == 2) return arap_cell_energy(data, embedded(U));
  ArapElements::ValueRows U_rows;
  std::vector<Eigen::Matrix3d> R;
  Eigen::VectorXd cell_energy;
  fit_rotations(data.elements, U, U_rows, R, cell_energy);
  return cell_energy;
}

Eigen::MatrixXd arap_gradient(const ArapData& data, const Eigen::MatrixXd& U) {
  check_solver_positions(data, U, data.V.rows(), "positions U");
  if (U.cols() == 2) return arap_gradient(data, embedded(U)).leftCols(2);
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

void rescale_report(ArapReport& report, double s) {
  const double energy_unit = s * s;
  report.initial_energy *= energy_unit;
  for (double& e : report.energies) e *= energy_unit;
  report.penalty *= energy_unit;
  report.arap_energy *= energy_unit;
  report.potential *= energy_unit;
  report.initial_gradient_norm *= s;
  for (double& g : report.gradient_norms) g *= s;
  report.newton_trust_radius *= s;
  report.newton_reference_gradient *= s;
}

FactorizationKind arap_factorization(const ArapData& data) {
  return data.solver.kind();
}

} // namespace iarap
