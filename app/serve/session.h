// The deformation session behind `iarap serve`: one mesh, its fixed and handle vertices, and one ARAP
// solver state per method (arap, spokes-rims, iarap). Not thread-safe: SharedSession (shared_session.h)
// guards it for the HTTP workers and runs its background refinement.
//
// Constrained vertices are fixed ++ handle, in that order. When they are set, each method records its
// current positions of them as anchors: fixed vertices stay at their anchors, handle vertices go to the
// anchors moved by the request's affine transform (or to explicit targets). Each method keeps its own
// deformed positions U, the warm start of its next solve, and its factorization, refactorized only when
// the constrained set changes (libigl habit: new targets reuse it). A mesh and targets in the plane z = 0
// are solved in that plane, as `iarap deform` does (ArapOptions::planar).
//
// The generation counts the states a frame can belong to: every solve and every change of constraints,
// shapes or mesh starts a new one, and ends the refinement of the previous one.
#pragma once
#include "constraint_history.h"
#include "drag_motion.h"
#include "frame_board.h"
#include "intrinsic_overlay.h"
#include "refine_job.h"
#include "solve_progress.h"
#include "solve_request.h"
#include "solver_constraints.h"

#include "iarap/core/errors.h"
#include "iarap/io/read_mesh.h"
#include "iarap/io/tet_mesh.h"
#include "iarap/registration/registration_target.h"
#include "iarap/solver/arap.h"

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace iarap::serve {

inline constexpr std::array<ArapMethod, 3> all_methods = {ArapMethod::Arap, ArapMethod::SpokesRims,
                                                          ArapMethod::Iarap};

// A request the session cannot serve in its present state (no mesh loaded, no constraints yet, an undo
// revision no longer kept): HTTP 409.
class SessionConflict : public InputError {
public:
  using InputError::InputError;
};

struct MeshSummary {
  std::string name;
  int vertices = 0, faces = 0; // a tetrahedral mesh: every vertex (interior ones too), its boundary faces
  int tetrahedra = 0;          // 0 for a triangle mesh
  double bbox_diagonal = 0;
  std::vector<std::string> notes, warnings; // reader notes and check_mesh warnings
};

// The constrained vertices of a method with their targets for a request, for saving them as a file.
struct ConstraintTargets {
  Eigen::VectorXi fixed, handle;
  Eigen::MatrixXd targets; // #fixed + #handle x 3, fixed rows first
  SoftConstraintSet soft;  // the session's soft constraints with their targets for the request
  // Every anchor is the vertex's rest position (to 1e-9 of the bounding-box diagonal): the targets are
  // then the rest mesh moved by the request.
  bool anchored_at_rest = false;
};

struct MeshSnapshot {
  Eigen::MatrixXd V;
  Eigen::MatrixXi F;
  std::string name;
};

// A fit's target (POST /api/target): what the viewer draws, and the target the registration fits to.
struct FitTarget {
  std::string name;
  RegistrationTarget target;
};

// What a fit (fit_runner.h) takes from the session when it starts: the rest mesh, the target and the
// generation the fit belongs to.
struct FitStart {
  Eigen::MatrixXd V;
  Eigen::MatrixXi F;
  std::shared_ptr<const FitTarget> target;
  std::uint64_t generation = 0;
};

class Session {
public:
  // Replaces the mesh (and clears constraints and solver states) after check_mesh. Throws TopologyError
  // listing check_mesh's errors; the previous mesh then stays.
  void load_mesh(const std::string& name, MeshData mesh);
  // A tetrahedral mesh (read_tet_mesh): deformed by the volumetric energy (arap_tets.h, method iarap only),
  // shown by its boundary faces (tet_boundary_faces: faces() and snapshot() give them; positions() every
  // vertex, interior ones included). Throws InputError without a tetrahedron, and what
  // arap_precompute_tets' checks throw (find_tet_problem).
  void load_tet_mesh(const std::string& name, TetMesh mesh);

  bool has_mesh() const { return mesh_.has_value(); }
  // The calls below throw SessionConflict when no mesh is loaded.
  const MeshSummary& mesh_summary() const;
  const Eigen::VectorXi& fixed() const;
  const Eigen::VectorXi& handle() const;
  const SoftSession& soft() const; // the loaded file's soft constraints, targets as loaded
  // The rigid groups (ArapOptions::rigid_groups) every method's setup uses; none after a load.
  const std::vector<Eigen::VectorXi>& rigid_groups() const;

  // Throws InputError naming the position for an index out of range, a repeat within a set, or a vertex
  // in both sets or also a soft vertex of the loaded file (kept: it stays soft); nothing changes then. Empty
  // sets are allowed (solve then throws SessionConflict). Returns the new revision: the sets with every
  // method's anchors, which restore_constraints brings back (undo).
  // rigid_groups: each at least 2 vertices, none in two groups (InputError naming rigid_groups[g][k]);
  // they may hold fixed or handle vertices, as `iarap deform --rigid` allows (the solver's checks apply at
  // the next solve).
  int set_constraints(const Eigen::VectorXi& fixed, const Eigen::VectorXi& handle,
                      const std::vector<Eigen::VectorXi>& rigid_groups = {});
  // Back to the sets and anchors of an earlier revision (one of the last ConstraintHistory::limit);
  // SessionConflict when it is no longer kept. U stays: the next solve moves the shape back.
  void restore_constraints(int revision);
  // The revision of the current sets and anchors (0 before any).
  int revision() const { return history_.newest(); }
  // Loads a saved constraint set: every method back to the rest shape, anchors = targets (#fixed +
  // #handle x 3), so a solve with no transform reaches them. Same checks as set_constraints, plus finite
  // targets. soft: the file's soft constraints (replacing the session's), anchored at their targets.
  // Returns the new revision.
  int load_constraints(const Eigen::VectorXi& fixed, const Eigen::VectorXi& handle,
                       const Eigen::MatrixXd& targets, const SoftSession& soft = {});
  // Where the method's constrained vertices go under request (its transform or handle_targets).
  ConstraintTargets constraint_targets(ArapMethod method, const SolveRequest& request) const;

  // Precomputes the method on first use (with the soft constraints), refactorizes after a constraint change
  // (precomputes again when the soft constraints or the planar mode changed), then runs arap_solve from
  // the method's current U as one call that reports every iteration to progress and stops early on a
  // cancel (keeping the last finished iterate). With request.refine_iterations > 0 and no convergence, a
  // refinement job is left for refine_chunk. Throws SessionConflict without constrained vertices or soft
  // constraints, TopologyError for forces on a connected component nothing holds, InputError for a target
  // shape or value at fault (forces of the wrong length, contradicting hard points on faces), TopologyError
  // / SolverError from the solver; the state is unchanged then.
  SolveResult solve(const SolveRequest& request, SolveProgress& progress);

  // The generation of the current state (see above).
  std::uint64_t generation() const { return generation_; }
  // A refinement job is pending (the last solve asked for one and it has not ended).
  bool refining() const { return refine_job_.has_value(); }
  // One chunk of the pending refinement (refine_job.h); the job ends when the frame says it is not
  // refining. Frame numbered by the caller's FrameBoard.
  SessionFrame refine_chunk(double budget_ms, const std::function<bool()>& keep_going,
                            const std::function<void()>& iteration_done = {});
  // Ends the pending refinement (its last iterate stays): the frame saying so, nullopt when none was pending.
  std::optional<SessionFrame> stop_refinement();

  // The target of the next fits, replacing any (a new mesh drops it); nullptr without one.
  void load_target(std::shared_ptr<const FitTarget> target);
  const std::shared_ptr<const FitTarget>& target() const;
  // A fit of the rest mesh to the target starts a new generation (ending the refinement). Throws
  // SessionConflict without a mesh or a target.
  FitStart begin_fit();
  // The fit's shape U (#V x 3) becomes the method's positions, its anchors re-taken there (a drag goes on
  // from the fitted shape), unless the session moved to another generation since begin_fit: false then,
  // and nothing changes.
  bool finish_fit(std::uint64_t generation, ArapMethod method, const Eigen::MatrixXd& U);

  // Every method back to the rest positions; anchors re-taken there; constraints and factorizations kept.
  void reset();

  // #V x 3 row-major current positions of a method, or the rest positions without one.
  std::vector<float> positions(std::optional<ArapMethod> method) const;
  // #F x 3 row-major face indices.
  std::vector<std::uint32_t> faces() const;
  // The method's current positions (the rest positions without one) with the faces, for writing a file.
  MeshSnapshot snapshot(std::optional<ArapMethod> method) const;
  // Built on first call for the rest mesh (intrinsic_delaunay), then cached until the next load.
  std::shared_ptr<const IntrinsicOverlay> intrinsic_overlay();

private:
  struct MethodState {
    std::optional<ArapData> data;  // built lazily; its fixed set may lag behind constrained_ until a solve
    Eigen::MatrixXd U;             // #V x 3 current positions
    Eigen::MatrixXd anchor;        // #constrained x 3 positions of the constrained vertices when set
    Eigen::MatrixXd soft_anchor;   // #soft x 3 positions of the soft points (solver order) when set
    int data_soft_version = 0;     // soft_version_ of the soft constraints data was built with
    bool data_soft_handle = false; // data was built with the handle as soft vertices
    int data_rigid_version = 0;    // rigid_version_ of the rigid groups data was built with
    DragMotion motion;             // the last answers' step, for SolveRequest::extrapolate
    // The accelerator's history (L-BFGS pairs, Anderson differences) from the drag's last update, carried
    // to the next: the targets moved by one step, the curvature the pairs hold stays that of a nearby
    // energy (ArapSolveOptions::accelerator_history). Kept and forgotten with `motion`.
    std::shared_ptr<ArapAcceleratorHistory> drag_history;
  };

  void require_mesh() const;
  void use_mesh(MeshData mesh, std::optional<Eigen::MatrixXi> tets); // the rest of a load
  void check_sets(const Eigen::VectorXi& fixed, const Eigen::VectorXi& handle,
                  const SoftConstraintSet& soft) const;
  void use_sets(const Eigen::VectorXi& fixed, const Eigen::VectorXi& handle,
                const std::vector<Eigen::VectorXi>& rigid_groups);
  int record_revision();
  MethodState& state_of(ArapMethod method);
  const MethodState& state_of(ArapMethod method) const;
  // True when it built or refactorized the method's data.
  bool prepare_data(MethodState& state, ArapMethod method, bool planar, const SolverConstraints& solver,
                    SolveResult& result);
  void new_generation(); // ends the refinement; a new state for frames
  void forget_motion();  // new constraints or positions: no drag to extrapolate

  // A tetrahedral mesh's volume energy (only iarap), or none; mesh_ then holds its boundary faces.
  void require_surface(const char* what) const;
  void require_method_for_mesh(ArapMethod method) const;

  std::optional<MeshData> mesh_;
  std::optional<Eigen::MatrixXi> tets_; // #T x 4 of a tetrahedral mesh
  MeshSummary summary_;
  Eigen::VectorXi fixed_, handle_, constrained_;
  SoftSession soft_;
  int soft_version_ = 0; // counts the soft sets loaded (a method's data is rebuilt for a new one)
  std::vector<Eigen::VectorXi> rigid_groups_;
  int rigid_version_ = 0; // counts the changes of rigid_groups_ (a method's data is rebuilt for a new set)
  std::array<MethodState, 3> methods_;
  std::shared_ptr<const IntrinsicOverlay> overlay_;
  std::shared_ptr<const FitTarget> target_;
  ConstraintHistory history_;
  std::uint64_t generation_ = 0;
  std::optional<RefineJob> refine_job_;
};

} // namespace iarap::serve
