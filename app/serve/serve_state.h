// The deformation session behind `iarap serve`: one mesh, its fixed and handle vertices, and one ARAP
// solver state per method (arap, spokes-rims, iarap), shared by all HTTP requests under one mutex.
//
// Constrained vertices are fixed ++ handle, in that order. When they are set, each method records its
// current positions of them as anchors: fixed vertices stay at their anchors, handle vertices go to the
// anchors moved by the request's affine transform (or to explicit targets). Each method keeps its own
// deformed positions U, the warm start of its next solve, and its factorization, refactorized only when
// the constrained set changes (libigl habit: new targets reuse it).
//
// A solve asked to refine keeps going toward its targets after answering, on the session's one background
// thread, in chunks of about refine_frame_ms that each publish a frame (FrameBoard). Every call that takes
// the session mutex preempts it at the next iteration boundary: the chunk's callback sees the caller
// waiting and stops, the last finished iterate is kept, and the caller gets the mutex. The generation
// counts the states a frame can belong to: every solve and every change of constraints, shapes or mesh
// starts a new one, and ends the refinement of the previous one.
#pragma once
#include "frame_board.h"
#include "solve_progress.h"

#include "iarap/core/stopwatch.h"
#include "iarap/intrinsic/intrinsic_delaunay.h"
#include "iarap/io/read_mesh.h"
#include "iarap/scene/constraint_set.h"
#include "iarap/solver/arap.h"

#include <Eigen/Core>
#include <array>
#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

namespace iarap::serve {

inline constexpr std::array<ArapMethod, 3> all_methods = {ArapMethod::Arap, ArapMethod::SpokesRims,
                                                          ArapMethod::Iarap};

struct MeshSummary {
  std::string name;
  int vertices = 0, faces = 0;
  double bbox_diagonal = 0;
  std::vector<std::string> notes, warnings; // reader notes and check_mesh warnings
};

// The server's solve options before a request sets any: the library's, but 5 iterations per answer (an
// interactive update; `refine` goes on in the background).
inline ArapSolveOptions interactive_solve_options() {
  ArapSolveOptions options;
  options.max_iterations = 5;
  return options;
}

// What a solve is asked to do. The solve options are the fields of solve_option_fields.h, parsed from the
// request by their names (solve_option_json.h); a new one needs nothing here.
struct SolveRequest {
  ArapMethod method = ArapMethod::Iarap;
  ArapSolveOptions solve = interactive_solve_options(); // max_iterations at most the server's limit
  // Handle targets: anchors moved by transform (4 x 4 affine, last row 0 0 0 1), or given as #handle x 3.
  std::optional<Eigen::Matrix4d> transform;
  std::optional<Eigen::MatrixXd> handle_targets;
  bool cell_energy = false; // also return arap_cell_energy of the result
  // Statics, as `iarap deform --gravity --density --forces`: forces f_i = m_i g (lumped masses of the
  // method, density x area) plus the given per-vertex forces (3 x #V numbers, row-major), and the solve
  // minimizes E_ARAP + P - f . (U - V). No gravity and no forces: the plain deformation.
  std::optional<Eigen::Vector3d> gravity;    // mesh units / time^2
  double density = 1.0;                      // surface density, > 0
  std::optional<std::vector<double>> forces; // 3 x #V numbers (checked against the mesh in solve)
  // > 0: unless the solve converged, keep solving toward the same targets in the background after the
  // answer (same method, accelerator, window and tolerance), at most this many more iterations.
  int refine_iterations = 0;
  // The refinement's accelerator. Newton by default: its end-game is the fastest (beetle, from a drag's
  // last answer: 31 iterations to a 3e-7 gap, where L-BFGS stopped at 5e-5 and Anderson at 6e-4), while
  // the drag's own updates are cheapest with plain iterations (bench/drag_bench.mjs).
  ArapAccelerator refine_accelerator = ArapAccelerator::Newton;
};

struct SolveResult {
  ArapReport report;
  double wait_ms = 0; // for the session: another request's work, or the refinement's last iteration
  bool refinement_preempted = false; // an unfinished refinement (of an earlier solve) ended for this one
  double precompute_ms = 0;          // > 0 when this solve built or refactorized the method's data
  double solve_ms = 0;
  int pinned = 0;                 // vertices pinned because their component had no constrained vertex
  std::vector<float> positions;   // #V x 3 row-major
  std::vector<float> cell_energy; // #V when requested
  bool cancelled = false;         // POST /api/cancel stopped it early; positions are the last iterate's
  std::uint64_t generation = 0;   // the session generation this solve started
  std::uint64_t sequence = 0;     // its frame's number on the FrameBoard
  bool refining = false;          // the background refinement continues from it
};

// The soft constraints of a loaded file (soft vertices, soft and hard points on faces): soft.*_targets are
// the file's. dragged (#soft vertices) marks the soft vertices a drag moves with the handle: those of a
// scenario's weighted handles, and in a constraints file those whose target is not their rest position.
// Points on faces are never dragged: they keep their targets.
struct SoftSession {
  SoftConstraintSet soft;
  std::vector<char> dragged;
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

// Intrinsic Delaunay edges traced over the input (TracedEdges, CSR): point p of edge e, for p in
// start[e] .. start[e+1]-1, is (1 - t[p]) U[a[p]] + t[p] U[c[p]] (c = -1: the vertex a[p]).
struct IntrinsicOverlay {
  std::vector<std::int32_t> start, a, c;
  std::vector<float> t;
  std::vector<std::int32_t> original; // #E 1 when the intrinsic edge is still an input edge
};

struct MeshSnapshot {
  Eigen::MatrixXd V;
  Eigen::MatrixXi F;
  std::string name;
};

class ServeState {
public:
  ServeState();  // starts the refinement thread
  ~ServeState(); // stops it at its next iteration boundary
  ServeState(const ServeState&) = delete;
  ServeState& operator=(const ServeState&) = delete;

  // How long one refinement chunk solves before it publishes a frame (the last iteration may run over).
  static constexpr double refine_frame_ms = 100;
  // The refinement starts once no caller has held the session for this long, so that it does not cost a
  // drag, whose next update comes within a frame of the pointer (16 ms at 60 Hz) plus a round trip.
  static constexpr double refine_delay_ms = 40;

  // Replaces the mesh (and clears constraints and solver states) after check_mesh. Throws TopologyError
  // listing check_mesh's errors; the previous mesh then stays.
  void load_mesh(const std::string& name, MeshData mesh);

  bool has_mesh() const;
  // The calls below throw HttpError 409 when no mesh is loaded.
  MeshSummary mesh_summary() const;
  Eigen::VectorXi fixed() const;
  Eigen::VectorXi handle() const;
  SoftSession soft() const; // the loaded file's soft constraints, targets as loaded

  // Throws InputError naming the position for an index out of range, a repeat within a set, or a vertex
  // in both sets or also a soft vertex of the loaded file (kept: it stays soft); nothing changes then. Empty
  // sets are allowed (solve then answers 409). Returns the new revision: the sets with every method's
  // anchors, which restore_constraints brings back (undo).
  int set_constraints(const Eigen::VectorXi& fixed, const Eigen::VectorXi& handle);
  // Back to the sets and anchors of an earlier revision (one of the last history_limit); HttpError 409
  // when it is no longer kept. U stays: the next solve moves the shape back.
  void restore_constraints(int revision);
  // The revision of the current sets and anchors (0 before any).
  int revision() const;
  // Loads a saved constraint set: every method back to the rest shape, anchors = targets (#fixed +
  // #handle x 3), so a solve with no transform reaches them. Same checks as set_constraints, plus finite
  // targets. soft: the file's soft constraints (replacing the session's), anchored at their targets.
  // Returns the new revision.
  int load_constraints(const Eigen::VectorXi& fixed, const Eigen::VectorXi& handle,
                       const Eigen::MatrixXd& targets, const SoftSession& soft = {});
  // Where the method's constrained vertices go under request (its transform or handle_targets).
  ConstraintTargets constraint_targets(ArapMethod method, const SolveRequest& request) const;

  // Precomputes the method on first use (with the soft constraints), refactorizes after a constraint change
  // (precomputes again when the soft constraints changed), then runs arap_solve from
  // the method's current U as one call that reports every iteration to progress() and stops early on a
  // cancel (keeping the last finished iterate). Throws HttpError 409 without constrained vertices or soft
  // constraints, 422 for forces on a connected component nothing holds, InputError for a target shape or
  // value at fault (forces of the wrong length, contradicting hard points on faces), TopologyError /
  // SolverError from the solver; the state is unchanged then.
  SolveResult solve(const SolveRequest& request);

  // Read without the session mutex (see SolveProgress).
  SolveProgress& progress() { return progress_; }
  // The answers and refinement frames, read without the session mutex.
  FrameBoard& frames() { return frames_; }
  // Ends the background refinement (its last iterate stays) and publishes a frame saying so; false when
  // none was running.
  bool stop_refinement();

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
    std::optional<ArapData> data; // built lazily; its fixed set may lag behind constrained_ until a solve
    Eigen::MatrixXd U;            // #V x 3 current positions
    Eigen::MatrixXd anchor;       // #constrained x 3 positions of the constrained vertices when set
    Eigen::MatrixXd soft_anchor;  // #soft x 3 positions of the soft points (solver order) when set
    int data_soft_version = 0;    // soft_version_ of the soft constraints data was built with
  };

  // What the background refinement works toward: a solve's targets and stopping rule.
  //
  // Its stopping rule is the request's, made independent of where the chunks begin: the energy rule
  // counts only accelerated iterates (a fallback plain step of Newton, L-BFGS or Anderson decreases the
  // energy little far from the minimum: 5e-7 of it at a 5e-4 gap on the beetle, which stopped the
  // refinement there), and the gradient rule compares with the gradient at the solve's initial guess.
  struct RefineJob {
    ArapMethod method = ArapMethod::Iarap;
    Eigen::MatrixXd targets, soft_targets; // options.forces: the solve's
    ArapSolveOptions options;              // max_iterations: the iterations left
    double tolerance = 0;                  // the energy rule (relative decrease of an accelerated iterate)
    double gradient_target = 0;            // stop once ||g|| <= this (0: no gradient rule)
    double gradient_now = 0;               // ||g|| at the method's U
    // Newton's trust radius and reference gradient, carried from the answer to the first chunk and from
    // chunk to chunk (same targets). Not from one answer to the next: carried over moved targets, the
    // radius of the previous step let the first steps of the beetle's drag run far (its last answer's
    // energy was 400 times the minimum's instead of 1.2 times).
    double trust_radius = 0, reference_gradient = 0;
    int iterations_done = 0;
  };

  // The session mutex, taken so that a running refinement chunk stops at its next iteration boundary:
  // waiting_ counts the callers queued for the mutex; the refinement thread is woken on release.
  class SessionLock {
  public:
    explicit SessionLock(const ServeState& state);
    ~SessionLock();
    SessionLock(const SessionLock&) = delete;
    SessionLock& operator=(const SessionLock&) = delete;

  private:
    const ServeState& state_;
    std::unique_lock<std::mutex> lock_;
  };

  struct Revision {
    int id = 0;
    Eigen::VectorXi fixed, handle;
    std::array<Eigen::MatrixXd, 3> anchors, soft_anchors;
    SoftSession soft;
    int soft_version = 0;
  };
  static constexpr std::size_t history_limit = 200;

  void require_mesh() const;
  void check_sets(const Eigen::VectorXi& fixed, const Eigen::VectorXi& handle,
                  const SoftConstraintSet& soft) const;
  void use_sets(const Eigen::VectorXi& fixed, const Eigen::VectorXi& handle);
  int record_revision();
  MethodState& state_of(ArapMethod method);
  const MethodState& state_of(ArapMethod method) const;
  Eigen::MatrixXd targets_for(const MethodState& state, const SolveRequest& request) const;
  Eigen::MatrixXd soft_targets_for(const MethodState& state, const SolveRequest& request) const;
  Eigen::MatrixXd forces_for(const SolveRequest& request) const; // 0 x 0 without gravity and forces
  void prepare_data(MethodState& state, ArapMethod method, SolveResult& result);
  void new_generation(); // ends the refinement; a new state for frames
  void refine_in_background();
  void refine_chunk(); // one chunk of refine_job_, with the session mutex held

  mutable std::mutex mutex_;
  std::optional<MeshData> mesh_;
  MeshSummary summary_;
  Eigen::VectorXi fixed_, handle_, constrained_;
  SoftSession soft_;
  int soft_version_ = 0; // counts the soft sets loaded (a method's data is rebuilt for a new one)
  std::array<MethodState, 3> methods_;
  std::shared_ptr<const IntrinsicOverlay> overlay_;
  std::deque<Revision> history_; // oldest first, at most history_limit
  int next_revision_ = 1;
  SolveProgress progress_;
  FrameBoard frames_;
  std::uint64_t generation_ = 0;
  std::optional<RefineJob> refine_job_;
  mutable std::atomic<int> waiting_{0};
  mutable std::condition_variable refine_wake_;
  mutable Clock::time_point last_release_; // when a caller last released the session (under mutex_)
  std::atomic<bool> stopping_{false};
  std::thread refiner_; // last: starts once everything above exists
};

} // namespace iarap::serve
