#include "session.h"

#include "request_targets.h"

#include "../common/explain_error.h"
#include "iarap/jobs/deform_job.h"
#include "iarap/jobs/soft_constraints.h"

#include "iarap/core/stopwatch.h"
#include "iarap/mesh/validate.h"
#include "iarap/solver/arap_tets.h"

#include <algorithm>
#include <cmath>
#include <unordered_map>

namespace iarap::serve {
namespace {

// The viewer loads a mesh as it is; the repair a warning names runs in the tool, before serving.
const std::string viewer_repair = std::string("outside the viewer, ") + cli::deform_repair_flag;

Eigen::MatrixXd gather_rows(const Eigen::MatrixXd& X, const Eigen::VectorXi& rows) {
  Eigen::MatrixXd out(rows.size(), X.cols());
  for (Eigen::Index i = 0; i < rows.size(); ++i) out.row(i) = X.row(rows[i]);
  return out;
}

// Range, repeats, and (against `other`) overlap; messages name set[position] = index.
void check_index_set(const Eigen::VectorXi& set, const char* name, int vertex_count,
                     std::unordered_map<int, std::string>& seen) {
  for (Eigen::Index i = 0; i < set.size(); ++i) {
    const std::string where = std::string(name) + "[" + std::to_string(i) + "] = " + std::to_string(set[i]);
    if (set[i] < 0 || set[i] >= vertex_count) {
      throw InputError(where + " is out of range; the mesh has " + std::to_string(vertex_count) +
                       " vertices (0-based indices)");
    }
    const auto [it, inserted] = seen.emplace(set[i], std::string(name) + "[" + std::to_string(i) + "]");
    if (!inserted) throw InputError(where + " repeats " + it->second);
  }
}

// Rigid groups as the page sends them: each of at least 2 vertices in range, no vertex in two groups (or
// twice in one), errors naming the position rigid_groups[g][k]. Sharing a vertex with the fixed or handle
// set is the solver's business (a held group), checked when the setup is built.
void check_rigid_group_lists(const std::vector<Eigen::VectorXi>& groups, int vertex_count) {
  std::unordered_map<int, std::string> seen;
  for (std::size_t g = 0; g < groups.size(); ++g) {
    const std::string name = "rigid_groups[" + std::to_string(g) + "]";
    if (groups[g].size() < 2) {
      throw InputError(name + " has " + std::to_string(groups[g].size()) +
                       " vertices; a rigid group needs at least 2");
    }
    check_index_set(groups[g], name.c_str(), vertex_count, seen);
  }
}

// The positions on U of the soft points in the solver's order: soft vertices, soft points on faces, hard
// points on faces (barycentric combinations of their face's corners).
Eigen::MatrixXd soft_points_at(const SoftConstraintSet& soft, const Eigen::MatrixXi& F,
                               const Eigen::MatrixXd& U) {
  Eigen::MatrixXd P(soft.size(), 3);
  Eigen::Index row = 0;
  for (Eigen::Index k = 0; k < soft.vertices.size(); ++k) P.row(row++) = U.row(soft.vertices[k]);
  const auto on_face = [&](int f, const auto& b) {
    return (b(0) * U.row(F(f, 0)) + b(1) * U.row(F(f, 1)) + b(2) * U.row(F(f, 2))).eval();
  };
  for (Eigen::Index k = 0; k < soft.faces.size(); ++k)
    P.row(row++) = on_face(soft.faces[k], soft.barycentric.row(k));
  for (Eigen::Index k = 0; k < soft.hard_faces.size(); ++k)
    P.row(row++) = on_face(soft.hard_faces[k], soft.hard_barycentric.row(k));
  return P;
}

// One arap_solve call that publishes its progress after every iteration and stops when a cancel is
// requested (the callback returns false). One call, not chunks: the accelerators keep their history, so the
// page's result equals `iarap deform`'s with the same options to rounding (not bit for bit: the first
// rotation fits start from the session's last ones, which on the beetle's drag made an update of one
// iteration cost half as much; ArapSolveOptions::warm_start_rotations).
ArapReport solve_with_progress(ArapData& data, const Eigen::MatrixXd& targets,
                               const Eigen::MatrixXd& soft_targets, const Eigen::MatrixXd& forces,
                               Eigen::MatrixXd& U, const SolveRequest& request, SolveProgress& progress,
                               std::shared_ptr<ArapAcceleratorHistory> history) {
  progress.cancel_requested = false;
  progress.method = static_cast<int>(request.method);
  progress.iteration = 0;
  progress.iterations = request.solve.max_iterations;
  progress.running = true;
  struct Done { // clears `running` on every exit, a throw included
    SolveProgress& progress;
    ~Done() { progress.running = false; }
  } done{progress};
  ArapSolveOptions options = request.solve;
  options.warm_start_rotations = true;
  options.accelerator_history = std::move(history);
  options.on_iteration = [&progress](const ArapReport& report) {
    progress.iteration = report.iterations;
    progress.energy = last_energy(report);
    return !progress.cancel_requested.load();
  };
  options.forces = forces;
  if (data.soft.size() == 0) return arap_solve(data, targets, U, options);
  return arap_solve(data, targets, soft_targets, U, options);
}

} // namespace

void Session::new_generation() {
  ++generation_;
  refine_job_.reset();
}

void Session::forget_motion() {
  for (MethodState& state : methods_) {
    state.motion.clear();
    state.drag_history.reset();
  }
}

void Session::load_mesh(const std::string& name, MeshData mesh) {
  const MeshReport report = check_mesh(mesh.V, mesh.F);
  if (!report.usable()) {
    std::string message = name + ": mesh not usable for ARAP:";
    for (const auto& error : report.errors) message += "\n  " + cli::name_repair(error, viewer_repair);
    throw TopologyError(message);
  }
  summary_ = MeshSummary{name,
                         static_cast<int>(mesh.V.rows()),
                         static_cast<int>(mesh.F.rows()),
                         0,
                         report.bbox_diagonal,
                         mesh.notes,
                         cli::name_repair(report.warnings, viewer_repair)};
  use_mesh(std::move(mesh), std::nullopt);
}

void Session::load_tet_mesh(const std::string& name, TetMesh tets) {
  if (tets.T.rows() == 0) throw InputError(name + ": the tetrahedral mesh has no tetrahedron");
  for (Eigen::Index v = 0; v < tets.V.rows(); ++v)
    if (!tets.V.row(v).allFinite())
      throw InputError(name + ": vertex " + std::to_string(v) + " is not finite");
  const TetProblem problem = find_tet_problem(tets.V, tets.T);
  if (problem.tet >= 0) throw InputError(name + ": " + problem.message);
  MeshData mesh;
  mesh.F = tet_boundary_faces(tets.T);
  mesh.V = std::move(tets.V);
  mesh.notes = std::move(tets.notes);
  summary_ = MeshSummary{name,
                         static_cast<int>(mesh.V.rows()),
                         static_cast<int>(mesh.F.rows()),
                         static_cast<int>(tets.T.rows()),
                         bounding_box_diagonal(mesh.V),
                         mesh.notes,
                         {}};
  use_mesh(std::move(mesh), std::move(tets.T));
}

void Session::use_mesh(MeshData mesh, std::optional<Eigen::MatrixXi> tets) {
  forget_motion();
  for (MethodState& state : methods_) {
    state.data.reset();
    state.U = mesh.V;
    state.anchor.resize(0, 3);
    state.soft_anchor.resize(0, 3);
  }
  soft_ = SoftSession{};
  ++soft_version_;
  fixed_.resize(0);
  handle_.resize(0);
  constrained_.resize(0);
  rigid_groups_.clear();
  ++rigid_version_;
  overlay_.reset();
  target_.reset(); // fitted to the previous mesh's scan
  new_generation();
  history_.clear(); // revisions index the previous mesh's vertices
  mesh_ = std::move(mesh);
  tets_ = std::move(tets);
}

void Session::require_mesh() const {
  if (!mesh_) throw SessionConflict("no mesh loaded; load one of the server's meshes or upload one first");
}

void Session::require_surface(const char* what) const {
  if (tets_)
    throw InputError(std::string(what) + " works on triangle meshes; " + summary_.name +
                     " is a tetrahedral mesh (shown by its boundary)");
}

void Session::require_method_for_mesh(ArapMethod method) const {
  if (tets_ && method != ArapMethod::Iarap)
    throw InputError(std::string("method ") + arap_method_name(method) + ": " + summary_.name +
                     " is a tetrahedral mesh, deformed by the volumetric ARAP energy only (method iarap)");
}

const MeshSummary& Session::mesh_summary() const {
  require_mesh();
  return summary_;
}

const Eigen::VectorXi& Session::fixed() const {
  require_mesh();
  return fixed_;
}

const Eigen::VectorXi& Session::handle() const {
  require_mesh();
  return handle_;
}

const SoftSession& Session::soft() const {
  require_mesh();
  return soft_;
}

const std::vector<Eigen::VectorXi>& Session::rigid_groups() const {
  require_mesh();
  return rigid_groups_;
}

// ArapMethod counts 0, 1, 2 in the order of all_methods.
Session::MethodState& Session::state_of(ArapMethod method) {
  return methods_[static_cast<std::size_t>(method)];
}

const Session::MethodState& Session::state_of(ArapMethod method) const {
  return methods_[static_cast<std::size_t>(method)];
}

void Session::check_sets(const Eigen::VectorXi& fixed, const Eigen::VectorXi& handle,
                         const SoftConstraintSet& soft) const {
  const int vertex_count = static_cast<int>(mesh_->V.rows());
  std::unordered_map<int, std::string> seen;
  for (Eigen::Index k = 0; k < soft.vertices.size(); ++k) {
    const auto at = static_cast<std::size_t>(k);
    seen.emplace(soft.vertices[k],
                 "a soft vertex of the loaded file" +
                     (at < soft.origins.size() ? " (" + soft.origins[at] + ")" : std::string()));
  }
  check_index_set(fixed, "fixed", vertex_count, seen);
  check_index_set(handle, "handle", vertex_count, seen);
}

void Session::use_sets(const Eigen::VectorXi& fixed, const Eigen::VectorXi& handle,
                       const std::vector<Eigen::VectorXi>& rigid_groups) {
  fixed_ = fixed;
  handle_ = handle;
  const bool same_groups =
      rigid_groups.size() == rigid_groups_.size() &&
      std::equal(rigid_groups.begin(), rigid_groups.end(), rigid_groups_.begin(), same_indices);
  if (!same_groups) {
    rigid_groups_ = rigid_groups;
    ++rigid_version_; // every method's setup is rebuilt with them at its next solve
  }
  constrained_.resize(fixed.size() + handle.size());
  constrained_ << fixed, handle;
}

int Session::record_revision() {
  Revision revision{0, fixed_, handle_, rigid_groups_, {}, {}, soft_, soft_version_};
  for (std::size_t m = 0; m < methods_.size(); ++m) {
    revision.anchors[m] = methods_[m].anchor;
    revision.soft_anchors[m] = methods_[m].soft_anchor;
  }
  return history_.record(std::move(revision));
}

int Session::set_constraints(const Eigen::VectorXi& fixed, const Eigen::VectorXi& handle,
                             const std::vector<Eigen::VectorXi>& rigid_groups) {
  require_mesh();
  check_sets(fixed, handle, soft_.soft);
  check_rigid_group_lists(rigid_groups, static_cast<int>(mesh_->V.rows()));
  use_sets(fixed, handle, rigid_groups);
  new_generation();
  forget_motion();
  // The dragged soft vertices are re-anchored where the shape put them, like the handle; the other soft
  // points keep their targets (soft: the shape does not reach them exactly).
  for (MethodState& state : methods_) {
    state.anchor = gather_rows(state.U, constrained_);
    for (Eigen::Index k = 0; k < soft_.soft.vertices.size(); ++k)
      if (soft_.dragged[static_cast<std::size_t>(k)])
        state.soft_anchor.row(k) = state.U.row(soft_.soft.vertices[k]);
  }
  return record_revision();
}

void Session::restore_constraints(int revision) {
  require_mesh();
  const Revision* restored = history_.restore(revision);
  if (restored == nullptr) {
    throw SessionConflict("constraint revision " + std::to_string(revision) + " is not kept (the last " +
                          std::to_string(ConstraintHistory::limit) + " of this mesh are)");
  }
  use_sets(restored->fixed, restored->handle, restored->rigid_groups);
  soft_ = restored->soft;
  soft_version_ = restored->soft_version;
  new_generation();
  forget_motion();
  for (std::size_t m = 0; m < methods_.size(); ++m) {
    methods_[m].anchor = restored->anchors[m];
    methods_[m].soft_anchor = restored->soft_anchors[m];
  }
}

int Session::load_constraints(const Eigen::VectorXi& fixed, const Eigen::VectorXi& handle,
                              const Eigen::MatrixXd& targets, const SoftSession& soft) {
  require_mesh();
  check_sets(fixed, handle, soft.soft);
  if (soft.dragged.size() != static_cast<std::size_t>(soft.soft.vertices.size()))
    throw InputError("soft constraints: the dragged marks do not match the soft vertices");
  if (targets.rows() != fixed.size() + handle.size() || targets.cols() != 3)
    throw InputError("constraint targets do not match the constrained vertices");
  for (Eigen::Index i = 0; i < targets.rows(); ++i) {
    if (!targets.row(i).allFinite())
      throw InputError("constraint target " + std::to_string(i) + " is not finite");
  }
  use_sets(fixed, handle, {}); // a constraints file or scenario names no rigid groups
  if (soft_.soft.size() > 0 || soft.soft.size() > 0) ++soft_version_; // rebuilt at the next solve
  soft_ = soft;
  new_generation();
  forget_motion();
  const Eigen::MatrixXd soft_targets = soft_targets_of(soft.soft);
  for (MethodState& state : methods_) {
    state.U = mesh_->V;
    state.anchor = targets;
    state.soft_anchor = soft_targets;
  }
  return record_revision();
}

ConstraintTargets Session::constraint_targets(ArapMethod method, const SolveRequest& request) const {
  require_mesh();
  if (constrained_.size() == 0 && soft_.soft.size() == 0)
    throw SessionConflict("no fixed or handle vertices; select some first");
  const MethodState& state = state_of(method);
  SoftConstraintSet file_soft = soft_.soft;
  set_soft_targets(file_soft, soft_point_targets(state.soft_anchor, soft_, request));
  // A soft handle is saved as the file's soft vertices ("index x y z w"), as the solver sees it.
  SolverConstraints solver =
      solver_constraints(fixed_, handle_, constrained_targets(state.anchor, handle_.size(), request),
                         file_soft, request.handle_weights);
  ConstraintTargets out;
  out.fixed = fixed_;
  out.handle = solver.soft_handle ? Eigen::VectorXi() : handle_;
  out.targets = std::move(solver.hard_targets);
  out.soft = std::move(solver.soft);
  // Anchors re-taken after a solve that kept the shape (e.g. a handle selected, the identity solved) differ
  // from the rest rows by the solve's rounding (1e-16 relative, times the conditioning of L); 1e-9 of the
  // bounding-box diagonal lies far above that and far below anything a user's drag moves.
  const Eigen::MatrixXd rest = gather_rows(mesh_->V, constrained_);
  out.anchored_at_rest =
      rest.size() == 0 || (state.anchor - rest).cwiseAbs().maxCoeff() <= 1e-9 * summary_.bbox_diagonal;
  return out;
}

// The method's data for the solver's constraints: built on first use, for new soft constraints (the
// file's, or a handle turned soft or hard), for a change of planar mode, or for new hard or soft sets while
// soft points exist; refactorized when only the hard set changed, or only a soft handle's weights.
bool Session::prepare_data(MethodState& state, ArapMethod method, bool planar,
                           const SolverConstraints& solver, SolveResult& result) {
  const auto precompute_start = Clock::now();
  const bool soft = solver.soft.size() > 0;
  if (!state.data || state.data_soft_version != soft_version_ || state.data->planar != planar ||
      state.data_soft_handle != solver.soft_handle || state.data_rigid_version != rigid_version_ ||
      (soft && (!same_indices(state.data->fixed, solver.hard) ||
                !same_indices(state.data->soft.vertices, solver.soft.vertices)))) {
    ArapOptions options;
    options.method = method;
    options.planar = planar;
    // Uploaded meshes may have pieces the user did not select; pin them rather than refuse to solve.
    options.pin_unconstrained_components = true;
    for (const Eigen::VectorXi& group : rigid_groups_)
      options.rigid_groups.emplace_back(group.data(), group.data() + group.size());
    state.data.reset(); // a throw leaves no data, rebuilt next time
    if (tets_) {
      state.data = !soft ? arap_precompute_tets(mesh_->V, *tets_, solver.hard, options)
                         : arap_precompute_tets(mesh_->V, *tets_, solver.hard,
                                                soft_constraints_of(solver.soft), options);
    } else {
      state.data =
          !soft ? arap_precompute(mesh_->V, mesh_->F, solver.hard, options)
                : arap_precompute(mesh_->V, mesh_->F, solver.hard, soft_constraints_of(solver.soft), options);
    }
    state.data_soft_version = soft_version_;
    state.data_soft_handle = solver.soft_handle;
    state.data_rigid_version = rigid_version_;
    result.precompute_ms = ms_since(precompute_start);
    return true;
  } else if (!same_indices(state.data->fixed, solver.hard)) {
    arap_set_fixed(*state.data, solver.hard); // keeps the previous set on a throw
    result.precompute_ms = ms_since(precompute_start);
    return true;
  } else if (solver.soft_handle && state.data->soft.vertex_weights != solver.soft.vertex_weights) {
    try { // a numeric refactorization; a throw leaves no data, rebuilt next time
      arap_set_soft_weights(*state.data, solver.soft.vertex_weights, solver.soft.face_weights);
    } catch (...) {
      state.data.reset();
      throw;
    }
    result.precompute_ms = ms_since(precompute_start);
    return true;
  }
  return false;
}

SolveResult Session::solve(const SolveRequest& request, SolveProgress& progress) {
  require_mesh();
  if (constrained_.size() == 0 && soft_.soft.size() == 0)
    throw SessionConflict("no fixed or handle vertices; select some before solving");
  require_method_for_mesh(request.method);
  // One rotation per tetrahedron, and masses of a volume: the surface's cell energies and forces do not
  // apply.
  if (request.cell_energy) require_surface("cell_energy (the energy per vertex)");
  if (request.gravity || request.forces) require_surface("gravity / forces in the viewer");
  MethodState& state = state_of(request.method);
  const Eigen::MatrixXd targets = constrained_targets(state.anchor, handle_.size(), request);
  SoftConstraintSet file_soft = soft_.soft;
  const Eigen::MatrixXd file_soft_targets = soft_point_targets(state.soft_anchor, soft_, request);
  set_soft_targets(file_soft, file_soft_targets);
  const SolverConstraints solver =
      solver_constraints(fixed_, handle_, targets, file_soft, request.handle_weights);
  const Eigen::MatrixXd soft_targets = soft_targets_of(solver.soft);
  const Eigen::MatrixXd forces = request_forces(*mesh_, constrained_, soft_.soft, request);
  SolveResult result;
  result.refinement_preempted = refine_job_.has_value();
  new_generation();
  // `iarap deform`'s rule (solve_deform): a mesh and targets in z = 0 deform in their plane. Its initial
  // guess is the rest mesh; the session's is the method's U, which must lie in the plane too.
  result.planar = !tets_ && deforms_in_plane(mesh_->V, targets, soft_targets, forces) &&
                  deforms_in_plane(state.U, Eigen::MatrixXd(), Eigen::MatrixXd(), Eigen::MatrixXd());
  // New data (another free set, the planar mode, soft terms): the drag's step and history are of another
  // problem (a history of another size is refused by the solver).
  if (prepare_data(state, request.method, result.planar, solver, result)) {
    state.motion.clear();
    state.drag_history.reset();
  }

  Eigen::MatrixXd U = state.U; // commit only a successful solve
  // Soft points and forces move the minimum without moving the hard targets: no prediction from those.
  const bool predict = request.extrapolate && solver.soft.size() == 0 && forces.size() == 0;
  if (predict) {
    result.extrapolation = state.motion.scale(solver.hard_targets);
    state.motion.extrapolate(result.extrapolation, U);
  }
  const auto solve_start = Clock::now();
  try {
    result.report = solve_with_progress(*state.data, solver.hard_targets, soft_targets, forces, U, request,
                                        progress, predict ? state.drag_history : nullptr);
  } catch (const HardPointConflict& e) {
    throw InputError(hard_point_conflict_message(e, solver.soft));
  }
  result.cancelled = result.report.stop_reason == ArapStopReason::Callback; // not a time budget
  result.solve_ms = ms_since(solve_start);
  result.pinned = static_cast<int>(state.data->pinned.size());
  result.positions = to_float_rows(U);
  if (request.cell_energy) {
    const Eigen::VectorXd energy = arap_cell_energy(*state.data, U);
    // iARAP with refine_boundary adds cells for inserted boundary points after the #V vertex cells.
    result.cell_energy.assign(energy.data(), energy.data() + std::min<Eigen::Index>(energy.size(), U.rows()));
  }
  if (predict && !result.cancelled) {
    state.motion.record(U, solver.hard_targets);
    state.drag_history = result.report.accelerator_history;
  } else {
    state.motion.clear();
    state.drag_history.reset();
  }
  state.U = std::move(U);
  result.generation = generation_;
  result.refining = request.refine_iterations > 0 && !result.report.converged && !result.cancelled;
  if (result.refining)
    refine_job_ = refine_job_after(request, result.report, solver.hard_targets, soft_targets, forces);
  return result;
}

SessionFrame Session::refine_chunk(double budget_ms, const std::function<bool()>& keep_going,
                                   const std::function<void()>& iteration_done) {
  RefineJob& job = *refine_job_;
  MethodState& state = state_of(job.method);
  SessionFrame frame = serve::refine_chunk(job, *state.data, state.U, budget_ms, keep_going, iteration_done);
  frame.generation = generation_;
  if (!frame.refining) refine_job_.reset();
  return frame;
}

std::optional<SessionFrame> Session::stop_refinement() {
  if (!refine_job_) return std::nullopt;
  const RefineJob job = std::move(*refine_job_);
  refine_job_.reset();
  const MethodState& state = state_of(job.method);
  SessionFrame frame = stopped_refinement_frame(job, *state.data, state.U, mesh_->V);
  frame.generation = generation_;
  return frame;
}

void Session::load_target(std::shared_ptr<const FitTarget> target) {
  require_mesh();
  target_ = std::move(target);
}

const std::shared_ptr<const FitTarget>& Session::target() const {
  require_mesh();
  return target_;
}

FitStart Session::begin_fit() {
  require_mesh();
  require_surface("fitting to a target");
  if (!target_) throw SessionConflict("no fit target loaded; upload a point cloud or mesh to fit first");
  new_generation();
  return {mesh_->V, mesh_->F, target_, generation_};
}

bool Session::finish_fit(std::uint64_t generation, ArapMethod method, const Eigen::MatrixXd& U) {
  if (!mesh_ || generation != generation_ || U.rows() != mesh_->V.rows()) return false;
  forget_motion();
  MethodState& state = state_of(method);
  state.U = U;
  state.anchor = gather_rows(U, constrained_);
  state.soft_anchor = soft_points_at(soft_.soft, mesh_->F, U);
  return true;
}

void Session::reset() {
  require_mesh();
  new_generation();
  forget_motion();
  for (MethodState& state : methods_) {
    state.U = mesh_->V;
    state.anchor = gather_rows(state.U, constrained_);
    state.soft_anchor = soft_points_at(soft_.soft, mesh_->F, state.U);
  }
  if (constrained_.size() > 0 || soft_.soft.size() > 0) record_revision();
}

std::vector<float> Session::positions(std::optional<ArapMethod> method) const {
  require_mesh();
  return to_float_rows(method ? state_of(*method).U : mesh_->V);
}

std::vector<std::uint32_t> Session::faces() const {
  require_mesh();
  const Eigen::MatrixXi& F = mesh_->F;
  std::vector<std::uint32_t> out(static_cast<std::size_t>(F.rows() * 3));
  for (Eigen::Index f = 0; f < F.rows(); ++f)
    for (int k = 0; k < 3; ++k)
      out[static_cast<std::size_t>(3 * f + k)] = static_cast<std::uint32_t>(F(f, k));
  return out;
}

MeshSnapshot Session::snapshot(std::optional<ArapMethod> method) const {
  require_mesh();
  return {method ? state_of(*method).U : mesh_->V, mesh_->F, summary_.name};
}

std::shared_ptr<const IntrinsicOverlay> Session::intrinsic_overlay() {
  require_mesh();
  require_surface("the intrinsic edge overlay");
  if (!overlay_)
    overlay_ = std::make_shared<const IntrinsicOverlay>(make_intrinsic_overlay(mesh_->V, mesh_->F));
  return overlay_;
}

} // namespace iarap::serve
