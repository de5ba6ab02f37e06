// The types of the ARAP solver (arap.h): the energy and accelerator choices, the options, the precomputed
// data and the report of a solve. The layers of src/solver below the facade read these, never arap.h.
#pragma once
#include "iarap/intrinsic/intrinsic_delaunay.h"
#include "iarap/solver/arap_elements.h"
#include "iarap/solver/arap_soft_constraints.h"
#include "iarap/solver/rigid_groups.h"
#include "iarap/solver/sparse_cholesky.h"

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace iarap {

enum class ArapMethod {
  Arap,       // original ARAP (Sorkine & Alexa 2007), cotan weights, negative ones kept (Eq. 1)
  SpokesRims, // spokes-and-rims (Chao et al. 2010), per-triangle cotangents (Eq. 2)
  Iarap,      // intrinsic ARAP: segments of the traced intrinsic Delaunay edges (Eq. 9, 11)
};

// "arap" | "spokes-rims" | "iarap"; anything else throws InputError naming the value and the choices.
ArapMethod parse_arap_method(const std::string& name);
// The inverse of parse_arap_method.
std::string arap_method_name(ArapMethod method);

// The intrinsic options ARAP uses by default: boundary refinement on (issue 8). On meshes with boundary
// the paper's iARAP keeps a negative weight on every boundary edge with an obtuse opposite angle and drifts
// at rest (measured: lion.off 4.1% of the bbox diagonal, beetle.off 0.39% after 50 iterations); refined,
// both stay within 1e-11 at an iteration cost within 10%. Closed meshes are unaffected (nothing is
// inserted). Set intrinsic.refine_boundary = false for the paper's exact discretization.
inline IntrinsicOptions boundary_robust_intrinsic_options() {
  IntrinsicOptions options;
  options.refine_boundary = true;
  return options;
}

struct ArapOptions {
  ArapMethod method = ArapMethod::Iarap;
  IntrinsicOptions intrinsic = boundary_robust_intrinsic_options(); // used by ArapMethod::Iarap only
  // A connected component without a constrained vertex makes L_ff singular. false: SolverError naming
  // it; true: its first (smallest-index) vertex is pinned where the initial guess of arap_solve puts it.
  // A vertex used by no face (no energy) is pinned either way: kept, where the initial guess puts it.
  bool pin_unconstrained_components = false;
  // A planar mesh deformed in its plane: cell rotations about the z axis only (2x2 rotations,
  // planar_rotation), so that a cell squeezed through a reflection is fitted the closest rotation, never
  // one that turns the plane over. V must then lie in the plane z = 0, and targets and positions too
  // (arap_solve). A #V x 2 V is planar whatever this says.
  bool planar = false;
  // #V factors s_i > 0 on the energy of vertex i's rotation cell, E = sum_i s_i E_i (issue 45): a stiffer
  // region bends and stretches less. Empty, or 1 everywhere: none (the same bytes). Every method's cells
  // are the vertices' (original ARAP: the spokes of i; spokes-and-rims: the spokes and rims of i's faces;
  // iARAP: the intrinsic spokes of i); a boundary point iARAP inserts takes the mean of the vertices its
  // elements reach. The rotations do not depend on it; L and the right-hand side weigh each cell's terms.
  Eigen::VectorXd stiffness;
  // CHOLMOD's fill-reducing ordering of L_ff (sparse_cholesky.h): Auto (AMD below a million free vertices,
  // METIS from there), AMD (the faster analysis) or METIS (the smaller factor). It changes the factor, not
  // the solution beyond rounding.
  FillOrdering ordering = FillOrdering::Auto;
  // Rigid parts (issue 45, rigid_groups.h): each group's vertices (0-based, at least 2, no vertex in two
  // groups) move as one rigid body, exactly. Empty: none. Solved with every accelerator (each group is one
  // body of 6 degrees of freedom: rigid_group_problem.h); arap_solve refuses rotation smoothing with groups.
  std::vector<std::vector<int>> rigid_groups;
  // Keep ArapData::elements' per-element arrays (b, s_hat, w, faces, cells and their transpose) after the
  // precompute. The iterations, energies, gradients and right-hand sides read the streamed layout, which
  // repeats them cell by cell, so by default they are released once it is built (about 300 bytes per
  // vertex: issue 44); callers that read data.elements' arrays set this. With rigid groups they are kept.
  bool keep_elements = false;
};

// Wall-clock parts of arap_precompute; they add up to its duration.
struct ArapPrecomputeTimings {
  double intrinsic_ms = 0; // intrinsic Delaunay flips, tracing and segments (iARAP only)
  double assembly_ms = 0;  // elements (with the layout the iterations stream) and L
  // Components, constraint check, L_ff / L_fc extraction and the numeric factorization, plus any wait for
  // the pattern of L and the symbolic analysis, which run on their own thread beside the element build when
  // there is more than one thread (and are part of factor_ms with one thread). For iARAP, whose L is twice
  // the cotan Laplacian of the input, the numeric factorization runs beside the intrinsic build as well;
  // factor_ms is what of it that build did not hide.
  double factor_ms = 0;
  // The symbolic analysis alone (CHOLMOD ordering), wherever it ran.
  double analyze_ms = 0;
};

// What the intrinsic triangulation looked like (iARAP only; zeros otherwise).
struct ArapIntrinsicSummary {
  long flips = 0;
  int non_delaunay_before = 0;
  int non_delaunay_after = 0;
  double mollify_delta = 0.0;
  Eigen::Index intrinsic_edges = 0;
  Eigen::Index segments = 0;
  int obtuse_boundary_before = 0; // boundary edges with an obtuse opposite angle (negative weight)
  int obtuse_boundary_after = 0;  // ... left after refine_boundary
  Eigen::Index inserted_points = 0;
  // Built on the tufted cover (input not an oriented manifold, or IntrinsicOptions::tufted_cover), with
  // this many cover vertices (docs/nonmanifold.md).
  bool tufted_cover = false;
  Eigen::Index cover_vertices = 0;
};

// Everything arap_solve needs, owned by value (copyable: a copy refactorizes; movable: cheap).
// Fields are public for inspection; change them only through the functions below.
namespace detail {
struct FreeRowSystem; // src/solver/free_row_system.h
} // namespace detail

struct ArapData {
  ArapMethod method = ArapMethod::Iarap;
  bool pin_unconstrained_components = false;
  bool planar = false;           // rotations about z only; positions in the plane z = 0 (ArapOptions::planar)
  Eigen::MatrixXd V;             // #V x 3 rest positions (z = 0 for planar data given as #V x 2)
  Eigen::MatrixXi F;             // #F x 3 faces
  ArapElements elements;         // the variant's elements (arap_elements.h)
  double min_weight = 0.0;       // the smallest element weight w_e (negative: a non-Delaunay cotan weight)
  Eigen::SparseMatrix<double> L; // #V x #V system matrix, sum_e |cells(e)| w_e b_e b_e^T
  // How many elements have w_e < 0 (counted before the element arrays are released).
  Eigen::Index negative_weights = 0;
  Eigen::VectorXi component; // #V connected component of each vertex
  int component_count = 0;
  Eigen::VectorXi fixed;     // #fixed user-constrained vertices, in the order of the targets rows
  Eigen::VectorXi pinned;    // vertices pinned by pin_unconstrained_components, and vertices used by no face
  Eigen::VectorXi free;      // #free the unconstrained vertices, increasing
  Eigen::VectorXi free_slot; // #V position of v in free, or -1 for constrained vertices
  Eigen::SparseMatrix<double>
      L_fc;                 // #free x (#fixed + #pinned): coupling to the constrained vertices (of L + Q)
  SparseCholesky solver;    // factorization of L_ff (#free x #free), of (L + Q)_ff with soft constraints
  ArapSoftConstraints soft; // the soft constraints (arap_soft_constraints.h; empty: none)
  Eigen::SparseMatrix<double> Q;  // #V x #V soft system part sum_k 2 W_k c_k c_k^T (0 x 0 without soft)
  std::vector<Eigen::Matrix3d> R; // one per cell (arap_rotations) for the last iterate of arap_solve
  RigidGroupSystem rigid;         // ArapOptions::rigid_groups' system (empty: none)
  // L's (L + Q's) free rows as the solves stream them, built by the first solve and kept for the next
  // (free_row_system.h); cleared where the constrained set or Q changes.
  std::shared_ptr<const detail::FreeRowSystem> free_rows;
  ArapPrecomputeTimings timings;
  ArapIntrinsicSummary intrinsic;
};

// How arap_solve speeds up the local/global iteration. Every accelerator reuses the one factorization of
// L_ff and keeps the energy monotone (see ArapSolveOptions::accelerator).
enum class ArapAccelerator {
  None,     // plain local/global block descent (Sec. 4.2): U_{k+1,f} = L_ff^{-1} (rhs_f(R*(U_k)) - L_fc U_c)
  Anderson, // Anderson acceleration of that fixed-point map (Peng et al. 2018) with their energy safeguard
  Lbfgs,    // L-BFGS on the rotation-minimized energy, initial inverse Hessian L_ff^{-1} (Liu et al. 2017)
  Newton,   // truncated Newton with the exact Hessian of that energy: trust-region CG preconditioned by L_ff
  Hybrid,   // L-BFGS while it makes progress, then Newton's end-game (ArapSolveOptions::accelerator)
};

// "none" | "anderson" | "lbfgs" | "newton" | "hybrid"; anything else throws InputError naming the value and
// the choices.
ArapAccelerator parse_arap_accelerator(const std::string& name);
// The inverse of parse_arap_accelerator.
std::string arap_accelerator_name(ArapAccelerator accelerator);

struct ArapReport;
// L-BFGS's pairs, Anderson's differences and the hybrid's phase after a solve
// (src/solver/accelerator_history.h; opaque): ArapReport::accelerator_history, to hand on as
// ArapSolveOptions::accelerator_history.
struct ArapAcceleratorHistory;

// Called after each iteration with the report so far, the last one included (whatever ended the solve);
// returning false stops the solve (converged stays false) unless a rule of the options already did. For
// progress display and for stopping on an outside criterion (the bench's energy gap).
using ArapIterationCallback = std::function<bool(const ArapReport&)>;

struct ArapSolveOptions {
  int max_iterations = 50;
  // Stop when E_prev - E <= tolerance * |E_prev| (relative energy decrease) or E == 0. A negative
  // tolerance disables the rule: exactly max_iterations iterations (benchmarks, stability tests).
  double tolerance = 1e-6;
  // Stop when ||g_k|| <= gradient_tolerance * ||g_0||, g the gradient of the energy at the free vertices
  // (Eq. 14 restricted to them; Frobenius norm) and g_0 its value at the initial guess. Unlike the energy
  // rule it does not stop on a stall. 0 disables the rule.
  double gradient_tolerance = 0.0;
  // The accelerator (see ArapAccelerator). Anderson: an accelerated iterate whose energy is above the last
  // accepted one is replaced by the plain iterate and the history restarts. L-BFGS: Armijo backtracking on
  // the rotation-minimized energy; when it fails, the plain step (which never increases the energy while
  // L_ff is positive definite) and a fresh history. Newton: a trust region; a step that achieves less than
  // 10% of the predicted decrease is replaced by the plain step. Default Newton: on the bend60 scene
  // (`iarap bench --converge 1e-6`, docs/accelerators.md) it ended at the lowest minimum found for all three
  // energies on bunny, beetle and armadillo, in over 30x fewer iterations and over 5.5x less time than
  // plain on spokes-rims and iARAP. Each Newton iteration runs up to `window` CG steps (one solve each):
  // for a bounded cost per iteration (interactive updates, as the viewer does) choose L-BFGS.
  ArapAccelerator accelerator = ArapAccelerator::Newton;
  // History length m of the accelerator (Anderson: past residual differences; L-BFGS: (s, y) pairs; Newton:
  // the CG steps per Newton step). 0 runs the plain iteration, bit for bit as ArapAccelerator::None.
  int window = 8;
  // Wall-clock budget in milliseconds (0: none): the solve stops after the iteration that ends past it,
  // counted from the start of arap_solve (report.stop_reason = TimeBudget). For interactive updates: an
  // answer in bounded time, the shape at that iterate (every iterate is whole and lowers the energy).
  double time_budget_ms = 0;
  // External forces f (#V x 3, planar data #V x 2 or x 3 with z = 0; 0 x 0: none), a linear term of the
  // energy: the solve minimizes E_ARAP + P - sum_i f_i . (U_i - V_i), the potential of constant forces
  // measured from the rest shape V (so that the relative-decrease rule does not depend on where the mesh
  // lies). The global step's right-hand side gains f at the free rows; every accelerator sees the same total
  // energy and gradient. A free component has no minimum under a force with a non-zero sum: give it a fixed
  // vertex or a soft point (dynamics, src/dynamics, makes every vertex one through its inertia). Gravity on
  // a lumped mass: f_i = m_i g (arap_vertex_masses, iarap/dynamics/simulation.h).
  Eigen::MatrixXd forces;
  // Warm start of Newton's state from an earlier solve's report (ArapReport::newton_trust_radius and
  // newton_reference_gradient), for a solve that continues one (the viewer's refinement in chunks) or
  // follows it on moved targets (a drag). 0: fresh, the radius from the first plain step's length and the
  // reference ||g_0|| of this solve's initial guess. The reference sets CG's forcing term
  // eta = min(0.5, sqrt(||g|| / reference)): a fresh one at every restart would give eta = 0.5 and lose
  // the superlinear end-game.
  double newton_trust_radius = 0;
  double newton_reference_gradient = 0;
  // Warm start of L-BFGS's (s, y) pairs, Anderson's residual differences and the hybrid's phase from an
  // earlier solve on the same data and targets (its ArapReport::accelerator_history), for a solve that
  // continues one (the viewer's refinement in chunks): the second call then goes on where the first stopped
  // instead of rebuilding the history from a plain step. The solve continues the history in place and the
  // report hands back the same object (no copy of its window x #free x 3 vectors). A history of another
  // accelerator or window is reset (a cold start); one of a problem of another size throws InputError.
  // Over moved targets the pairs are those of a nearby energy: still safe (every step is checked), not
  // always faster. Null: cold, as before.
  std::shared_ptr<ArapAcceleratorHistory> accelerator_history;
  // Rotation smoothing ALPHA >= 0 (issue 45, docs/smoothing.md): the energy gains
  // (ALPHA A / 2) sum_i (1 / (2 d_i)) sum_{j in N(i)} |R_i - R_j|_F^2 (A the rest area, N(i) the cells
  // sharing an element with i's, d_i their number), the symmetric form of CGAL's SRE_ARAP with its alpha
  // (the / 2: our data term is half CGAL's). The local step then solves for all rotations at once; every
  // accelerator sees the total. 0: none, the same bytes as without. Refused on planar and tetrahedral data.
  double rotation_smoothing = 0;
  // Start the first local step's rotation fits from data.R, the rotations an earlier solve on the same data
  // left (polar_rotation_near: two or three Newton steps per cell against a cold fit's five to eight or an
  // SVD), instead of cold. The rotations are the same to rounding either way (the fit is unique), so a
  // solve's result changes only by rounding with what earlier solves left; off by default, so that a
  // result depends on its inputs only, bit for bit. For callers that solve the same data again and again
  // from nearby positions: the viewer's drag, whose every update is a new solve (a cold fit was the larger
  // part of an update on the beetle, issue 48). Without rotation smoothing and rigid groups (their local
  // steps start cold).
  bool warm_start_rotations = false;
  ArapIterationCallback on_iteration; // optional
  // Optional, for a caller that shares the solver with others (the viewer's background refinement, which
  // a drag's update preempts): checked between Newton's CG steps, and true ends the iteration's CG there
  // with the step found so far (a truncated CG step, as at CG's own stopping rule), so that on_iteration
  // comes within about one plain iteration (a CG step is one back-substitution and one Hessian product)
  // instead of a whole Newton iteration (up to `window` of them). Never true: the same iterates bit for bit.
  std::function<bool()> should_yield;
};

// Why arap_solve stopped.
enum class ArapStopReason {
  MaxIterations,     // options.max_iterations ran (also 0 iterations)
  EnergyTolerance,   // the relative energy decrease fell to options.tolerance, or E == 0
  GradientTolerance, // ||g|| fell to options.gradient_tolerance ||g_0||
  TimeBudget,        // the iteration that ended past options.time_budget_ms
  Callback,          // on_iteration returned false
};

// "max_iterations" | "energy_tolerance" | "gradient_tolerance" | "time_budget" | "callback".
std::string arap_stop_reason_name(ArapStopReason reason);

struct ArapReport {
  int iterations = 0;           // accepted iterates (each one global solve at least)
  double initial_energy = 0;    // E of the initial guess once the constrained rows are set to the targets
  std::vector<double> energies; // E(U_k) = min_R energy after each iteration k (size iterations); with soft
                                // constraints and forces the total E_ARAP + P + potential
  double penalty = 0;           // P(U) of the returned U (0 without soft constraints)
  double potential = 0;         // -sum_i f_i . (U_i - V_i) of the returned U (0 without forces)
  double arap_energy = 0;       // E_ARAP(U) of the returned U: the last energy (or initial_energy) - penalty
                                // - potential
  double local_ms = 0;          // all local steps, including the one that evaluates the last iterate
  double global_ms = 0;         // all global steps (right-hand side, solve and gradient)
  bool converged = false;       // a tolerance rule stopped the iteration (false: max_iterations or callback)
  ArapStopReason stop_reason = ArapStopReason::MaxIterations;
  std::vector<double> local_ms_per_iteration;          // the local step(s) evaluating U_k (size iterations)
  std::vector<double> global_ms_per_iteration;         // the global step producing U_k (size iterations)
  ArapAccelerator accelerator = ArapAccelerator::None; // what ran (None also for window 0)
  double initial_gradient_norm = 0;                    // ||g_0|| at the free vertices
  std::vector<double> gradient_norms;                  // ||g(U_k)|| at the free vertices (size iterations)
  // Per iteration: 1 when U_k came from the accelerator (an Anderson combination or an L-BFGS step with
  // history), 0 when it is the plain local/global iterate (first step, after a rejection, or no accelerator).
  std::vector<unsigned char> accepted;
  int rejected = 0;               // accelerated iterates refused by the energy safeguard / line search
  int solves = 0;                 // back-substitutions with the factor of L_ff: one per plain step, plus
                                  // L-BFGS's one per direction and Newton's one per conjugate-gradient step
  double accelerator_ms = 0;      // the accelerator's own work (history, least squares, two-loop recursion)
  std::vector<double> elapsed_ms; // wall time from the start of arap_solve to the end of iteration k
  // Newton only (0 otherwise): the trust radius (L_ff norm) and the reference gradient norm after the last
  // iteration, to pass on as ArapSolveOptions::newton_trust_radius / newton_reference_gradient.
  double newton_trust_radius = 0;
  double newton_reference_gradient = 0;
  // L-BFGS, Anderson and hybrid only (null otherwise): their history after the last iteration, to pass on as
  // ArapSolveOptions::accelerator_history.
  std::shared_ptr<ArapAcceleratorHistory> accelerator_history;
  // Hybrid only: the iteration (1-based) whose step was Newton's first; 0 while it has not switched.
  int newton_from_iteration = 0;
};

} // namespace iarap
