// Non-rigid registration (issue 46): deforms a source triangle mesh onto a target surface or point cloud by
// iterative closest points with the ARAP energy as the regularizer (non-rigid ICP):
//
//   RegistrationTarget target = read_registration_target("scan.xyz");     // or make_registration_target
//   RegistrationResult fit = register_to_target(V, F, target, landmarks);  // fit.U: V deformed, same rows
//
// 1. Pre-alignment: a rigid (or similarity) transform from the landmarks (>= 3) or the centroids, then
//    refined by rigid ICP (closest points, rejection, robust weights, fit_similarity) until it settles.
// 2. Stages from stiff to soft: stage s pulls every source vertex toward its correspondence with weight
//    w_s a_i (a_i the vertex's area over the mean, w_s growing geometrically from initial_data_weight to
//    final_data_weight), against E_ARAP of the pre-aligned source; the landmarks pull with their own weight.
// 3. Rounds within a stage: closest points both ways (correspondences.cpp), rejection by distance (over
//    reject_distance times the median) and normal angle, Welsch weights on the residual, then one
//    warm-started arap_solve. The per-vertex weights change every round (robust weights):
//    arap_set_soft_weights, a numeric refactorization only; the symbolic analysis and the precomputation are
//    made once. A stage ends when the mean distance changes by less than stage_tolerance, or after
//    rounds_per_stage rounds.
#pragma once
#include "iarap/registration/registration_target.h"
#include "iarap/registration/rigid_alignment.h"
#include "iarap/solver/arap_types.h"

#include <Eigen/Core>

#include <functional>
#include <string>
#include <vector>

namespace iarap {

// Points of the source held near given positions, each with its own weight W (penalty W |x - target|^2).
struct RegistrationLandmarks {
  Eigen::VectorXi vertices;       // #lv source vertices, distinct
  Eigen::MatrixXd vertex_targets; // #lv x 3
  Eigen::VectorXd vertex_weights; // #lv, > 0 (empty: RegistrationOptions::landmark_weight each)
  Eigen::VectorXi faces;          // #lb source faces
  Eigen::MatrixXd barycentric;    // #lb x 3, rows summing to 1
  Eigen::MatrixXd face_targets;   // #lb x 3
  Eigen::VectorXd face_weights;   // #lb, > 0 (empty: landmark_weight each)
  Eigen::Index size() const { return vertices.size() + faces.size(); }
};

enum class Prealignment { None, Rigid, Similarity };

// "none" | "rigid" | "similarity"; anything else throws InputError naming the value and the choices.
Prealignment parse_prealignment(const std::string& name);

struct RegistrationRound {
  int stage = 0, round = 0;   // 0-based
  double data_weight = 0;     // w_s
  double mean_distance = 0;   // source -> target closest-point distance at the round's start, mean (units)
  double median_distance = 0; // ... and median
  Eigen::Index forward_used = 0, backward_used = 0; // correspondences kept after rejection, both ways
  int solver_iterations = 0;
  double energy = 0;     // E_ARAP + P after the solve
  double closest_ms = 0; // closest-point queries, rejection and robust weights
  double factor_ms = 0;  // arap_set_soft_weights (numeric refactorization)
  double solve_ms = 0;   // arap_solve
};

// Calls f(name, value) for each field of a round, the distances as fractions of `diagonal` (the target's):
// the one field list the tool's JSON report and the Python report are written from.
template <class Visitor>
void visit_registration_round(const RegistrationRound& r, double diagonal, Visitor&& f) {
  f("stage", r.stage);
  f("round", r.round);
  f("data_weight", r.data_weight);
  f("mean_distance", r.mean_distance / diagonal);
  f("median_distance", r.median_distance / diagonal);
  f("forward_used", r.forward_used);
  f("backward_used", r.backward_used);
  f("solver_iterations", r.solver_iterations);
  f("energy", r.energy);
  f("closest_ms", r.closest_ms);
  f("factor_ms", r.factor_ms);
  f("solve_ms", r.solve_ms);
}

// Distances of the result's vertices to the target (closest point), as fractions of the target's diagonal.
struct DistanceStatistics {
  double mean = 0, median = 0, p90 = 0, max = 0;
};

// Calls f(name, value) for mean, median, p90 and max.
template <class Visitor> void visit_distance_statistics(const DistanceStatistics& s, Visitor&& f) {
  f("mean", s.mean);
  f("median", s.median);
  f("p90", s.p90);
  f("max", s.max);
}

struct RegistrationReport {
  SimilarityTransform prealignment; // source -> target, applied before the non-rigid stages
  int prealign_rounds = 0;
  std::vector<RegistrationRound> rounds;
  DistanceStatistics initial_distance; // after the pre-alignment
  DistanceStatistics final_distance;
  double target_diagonal = 0;
  double prealign_ms = 0, precompute_ms = 0, closest_ms = 0, factor_ms = 0, solve_ms = 0, total_ms = 0;
  bool stopped = false; // RegistrationOptions::on_round_shape returned false before the last round
};

struct RegistrationOptions {
  ArapMethod method = ArapMethod::Iarap;
  // Per round (warm-started): 3 plain iterations, since the targets move little between rounds. Measured
  // against 8 Newton iterations (examples/register_scan, mean / 90th percentile vertex error of the
  // diagonal): elephant 0.0035 / 0.0098 against 0.0036 / 0.0100, camelhead 0.0043 / 0.0085 against
  // 0.0045 / 0.0097, in 1.7 s against 2.6 s and 3.6 s against 4.9 s.
  ArapSolveOptions solve = default_round_solve();
  Prealignment prealignment = Prealignment::Rigid;
  int prealign_rounds = 50;
  // More stages and rounds cost time and gain accuracy (elephant bent + warped, scan with a hole, mean vertex
  // error / diagonal: 5 x 15 0.0064 in 2.1 s, 5 x 30 0.0047 in 2.6 s, 8 x 30 0.0041 in 2.9 s, 10 x 30 0.0038
  // in 3.2 s); a stage usually settles (stage_tolerance) before its last round.
  int stages = 8;
  int rounds_per_stage = 30;
  double initial_data_weight = 0.02; // w_0 (stiff: ARAP dominates, the fit is nearly rigid)
  double final_data_weight = 1.0;    // w_{stages-1} (soft; higher fits the target's noise)
  double landmark_weight = 100.0;
  // Soft target of a correspondence (p on the source, q on the target with normal n):
  // (1 - point_to_plane) q + point_to_plane (p - ((p - q) . n) n), a blend of point-to-point and of the
  // projection onto q's tangent plane (point-to-plane as a moved soft target, lets the source slide along
  // the surface).
  double point_to_plane = 0.95;
  // Weight of the target -> source correspondences against the forward ones (scaled by #V / #P, so that the
  // two weigh alike at 1 whatever the target's density). On the test scans, where the target covers the
  // source, they do not help: mean vertex error / diagonal on elephant 0.0039 at 0, 0.0041 at 0.1, 0.0071 at
  // 0.5 with 5 x 15 rounds (their spread over a face's corners blurs); kept small for targets the forward
  // search does not reach everywhere.
  double backward_weight = 0.1;
  double reject_distance = 3.0;     // reject correspondences farther than this times the median distance
  double reject_angle_degrees = 60; // ... and those whose normals differ by more than this
  double robust_scale = 2.0;        // Welsch's sigma = this times the median distance of the kept ones
  double stage_tolerance = 2e-3;    // relative change of the mean distance that ends a stage
  std::function<void(const RegistrationRound&)> on_round; // optional progress callback
  // Optional, after on_round: the round with the source as that round's solve left it (#V x 3). Returning
  // false stops the registration there (an interactive client's cancel): the result is that shape, with
  // report.stopped set and final_distance measured on it.
  std::function<bool(const RegistrationRound&, const Eigen::MatrixXd& U)> on_round_shape;

  static ArapSolveOptions default_round_solve() {
    ArapSolveOptions solve;
    solve.max_iterations = 3;
    solve.accelerator = ArapAccelerator::None;
    solve.tolerance = 1e-5;
    return solve;
  }
};

struct RegistrationResult {
  Eigen::MatrixXd U; // #V x 3: the source deformed onto the target, same vertex order as V
  RegistrationReport report;
};

// Registers the source mesh (V #V x 3, F #F x 3, a mesh arap_precompute accepts) to `target`. Throws
// InputError for a landmark out of range (naming it and the source's size), a bad landmark weight or
// barycentric row, bad options (naming the field); what arap_precompute and arap_solve throw.
RegistrationResult register_to_target(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F,
                                      const RegistrationTarget& target,
                                      const RegistrationLandmarks& landmarks = {},
                                      const RegistrationOptions& options = {});

// The distance statistics of points U (#U x 3) to the target, as fractions of target.diagonal.
DistanceStatistics distance_statistics(const Eigen::MatrixXd& U, const RegistrationTarget& target);

} // namespace iarap
