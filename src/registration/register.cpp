// The non-rigid ICP loop of register.h on the solver's facade: one arap_precompute with a soft point on
// every source vertex (and the face landmarks), then per round new weights (arap_set_soft_weights: numeric
// refactorization) and new targets (arap_solve, warm-started).
#include "iarap/registration/register.h"

#include "../core/math_constants.h"
#include "correspondences.h"
#include "iarap/core/errors.h"
#include "iarap/core/stopwatch.h"
#include "iarap/registration/surface_normals.h"
#include "iarap/solver/arap.h"
#include "prealign.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <string>

namespace iarap {

using registration_detail::CorrespondenceRules;
using registration_detail::LandmarkPoints;
using registration_detail::VertexPulls;

namespace {

void require(bool ok, const std::string& message) {
  if (!ok) throw InputError("register: " + message);
}

void check_options(const RegistrationOptions& o) {
  const auto positive = [](double x) { return std::isfinite(x) && x > 0; };
  require(o.stages >= 1, "stages must be >= 1; got " + std::to_string(o.stages));
  require(o.rounds_per_stage >= 1,
          "rounds_per_stage must be >= 1; got " + std::to_string(o.rounds_per_stage));
  require(o.prealign_rounds >= 0, "prealign_rounds must be >= 0; got " + std::to_string(o.prealign_rounds));
  require(positive(o.initial_data_weight), "initial_data_weight must be finite and > 0");
  require(positive(o.final_data_weight), "final_data_weight must be finite and > 0");
  require(positive(o.landmark_weight), "landmark_weight must be finite and > 0");
  require(o.point_to_plane >= 0 && o.point_to_plane <= 1, "point_to_plane must be in [0, 1]");
  require(std::isfinite(o.backward_weight) && o.backward_weight >= 0,
          "backward_weight must be finite and >= 0");
  require(positive(o.reject_distance), "reject_distance must be finite and > 0");
  require(o.reject_angle_degrees > 0 && o.reject_angle_degrees <= 180,
          "reject_angle_degrees must be in (0, 180]");
  require(positive(o.robust_scale), "robust_scale must be finite and > 0");
  require(std::isfinite(o.stage_tolerance) && o.stage_tolerance >= 0,
          "stage_tolerance must be finite and >= 0");
}

Eigen::VectorXd weights_or_default(const Eigen::VectorXd& given, Eigen::Index n, double fallback,
                                   const char* name) {
  if (given.size() == 0) return Eigen::VectorXd::Constant(n, fallback);
  require(given.size() == n, std::string(name) + " must have one weight per landmark");
  for (Eigen::Index k = 0; k < n; ++k)
    require(std::isfinite(given(k)) && given(k) > 0, std::string(name) + " " + std::to_string(k) +
                                                         " must be finite and > 0; got " +
                                                         std::to_string(given(k)));
  return given;
}

// The landmarks checked against the source and evaluated on V (rest positions), vertices first.
LandmarkPoints landmark_points(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F,
                               const RegistrationLandmarks& l, double landmark_weight) {
  const Eigen::Index nv = l.vertices.size(), nb = l.faces.size();
  require(l.vertex_targets.rows() == nv && (nv == 0 || l.vertex_targets.cols() == 3),
          "landmark vertex_targets must be #vertices x 3");
  require(l.face_targets.rows() == nb && (nb == 0 || l.face_targets.cols() == 3),
          "landmark face_targets must be #faces x 3");
  require(l.barycentric.rows() == nb && (nb == 0 || l.barycentric.cols() == 3),
          "landmark barycentric must be #faces x 3");
  LandmarkPoints points;
  points.source.resize(nv + nb, 3);
  points.target.resize(nv + nb, 3);
  points.weight.resize(nv + nb);
  points.weight.head(nv) =
      weights_or_default(l.vertex_weights, nv, landmark_weight, "landmark vertex weight");
  points.weight.tail(nb) = weights_or_default(l.face_weights, nb, landmark_weight, "landmark face weight");
  std::vector<char> seen(static_cast<std::size_t>(V.rows()), 0);
  for (Eigen::Index k = 0; k < nv; ++k) {
    const int v = l.vertices(k);
    require(v >= 0 && v < V.rows(), "landmark " + std::to_string(k) + ": vertex " + std::to_string(v) +
                                        " out of range; the source has " + std::to_string(V.rows()) +
                                        " vertices");
    require(!seen[static_cast<std::size_t>(v)],
            "landmark " + std::to_string(k) + ": vertex " + std::to_string(v) + " has a landmark already");
    seen[static_cast<std::size_t>(v)] = 1;
    require(l.vertex_targets.row(k).allFinite(), "landmark " + std::to_string(k) + ": target not finite");
    points.source.row(k) = V.row(v);
    points.target.row(k) = l.vertex_targets.row(k);
  }
  for (Eigen::Index k = 0; k < nb; ++k) {
    const int f = l.faces(k);
    const std::string name = "face landmark " + std::to_string(k);
    require(f >= 0 && f < F.rows(), name + ": face " + std::to_string(f) + " out of range; the source has " +
                                        std::to_string(F.rows()) + " faces");
    require(l.barycentric.row(k).allFinite() && std::abs(l.barycentric.row(k).sum() - 1) <= 1e-9,
            name + ": barycentric coordinates must be finite and sum to 1");
    require(l.face_targets.row(k).allFinite(), name + ": target not finite");
    points.source.row(nv + k) = l.barycentric(k, 0) * V.row(F(f, 0)) + l.barycentric(k, 1) * V.row(F(f, 1)) +
                                l.barycentric(k, 2) * V.row(F(f, 2));
    points.target.row(nv + k) = l.face_targets.row(k);
  }
  return points;
}

// A_i / mean(A): each vertex's share of the area (a third of its faces'), over the mean share.
Eigen::VectorXd relative_vertex_areas(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F) {
  Eigen::VectorXd A = Eigen::VectorXd::Zero(V.rows());
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    const Eigen::Vector3d a = V.row(F(f, 0)), b = V.row(F(f, 1)), c = V.row(F(f, 2));
    const double third = (b - a).cross(c - a).norm() / 6;
    for (int k = 0; k < 3; ++k) A(F(f, k)) += third;
  }
  const double mean = A.mean();
  return mean > 0 ? Eigen::VectorXd(A / mean) : Eigen::VectorXd::Ones(V.rows());
}

double data_weight(const RegistrationOptions& o, int stage) {
  if (o.stages == 1) return o.final_data_weight;
  const double t = static_cast<double>(stage) / (o.stages - 1);
  return o.initial_data_weight * std::pow(o.final_data_weight / o.initial_data_weight, t);
}

CorrespondenceRules correspondence_rules(const RegistrationOptions& options, double diagonal) {
  CorrespondenceRules rules;
  rules.point_to_plane = options.point_to_plane;
  rules.reject_distance = options.reject_distance;
  rules.cos_reject_angle = std::cos(options.reject_angle_degrees * kPi / 180);
  rules.robust_scale = options.robust_scale;
  rules.floor_distance = 1e-12 * diagonal;
  return rules;
}

// The solver's soft points: every vertex (weight w0 until the first round sets the data weights), then the
// face landmarks with their own weights.
ArapSoftConstraints soft_points(Eigen::Index n, const RegistrationLandmarks& landmarks,
                                const LandmarkPoints& points, double w0) {
  const Eigen::Index nb = landmarks.faces.size();
  ArapSoftConstraints soft;
  soft.vertices = Eigen::VectorXi::LinSpaced(n, 0, static_cast<int>(n - 1));
  soft.vertex_weights = Eigen::VectorXd::Constant(n, w0);
  soft.faces = landmarks.faces;
  soft.barycentric = nb > 0 ? landmarks.barycentric : Eigen::MatrixXd(0, 3);
  soft.face_weights = points.weight.tail(nb);
  return soft;
}

// The per-vertex soft weights and targets of a round: the data pulls (forward scaled by w_s a_i, backward
// by w_s backward_share), the vertex landmarks, and a floor of 1e-6 w_s toward the current position so that
// every weight stays > 0 (the solver's contract) for vertices without a kept correspondence.
void combine(const VertexPulls& forward, const VertexPulls& backward, double backward_share, double w_s,
             const Eigen::VectorXd& areas, const RegistrationLandmarks& landmarks,
             const LandmarkPoints& points, const Eigen::MatrixXd& U, Eigen::VectorXd& W, Eigen::MatrixXd& T) {
  const double floor = 1e-6 * w_s;
  W = Eigen::VectorXd::Constant(U.rows(), floor);
  T = floor * U;
  for (Eigen::Index i = 0; i < U.rows(); ++i) {
    const double wf = w_s * areas(i) * forward.weight(i);
    W(i) += wf;
    T.row(i) += wf * forward.target.row(i);
    if (backward.weight.size() > 0) {
      const double wb = w_s * backward_share * backward.weight(i); // already area-proportional
      W(i) += wb;
      T.row(i) += wb * backward.target.row(i);
    }
  }
  for (Eigen::Index k = 0; k < landmarks.vertices.size(); ++k) {
    const int v = landmarks.vertices(k);
    W(v) += points.weight(k);
    T.row(v) += points.weight(k) * points.target.row(k);
  }
  T.array().colwise() /= W.array();
}

} // namespace

Prealignment parse_prealignment(const std::string& name) {
  if (name == "none") return Prealignment::None;
  if (name == "rigid") return Prealignment::Rigid;
  if (name == "similarity") return Prealignment::Similarity;
  throw InputError("prealign must be 'none', 'rigid' or 'similarity'; got '" + name + "'");
}

DistanceStatistics distance_statistics(const Eigen::MatrixXd& U, const RegistrationTarget& target) {
  DistanceStatistics s;
  if (U.rows() == 0 || !(target.diagonal > 0)) return s;
  Eigen::VectorXd d = registration_detail::closest_target_points(U, target).distance / target.diagonal;
  std::sort(d.data(), d.data() + d.size());
  const auto at = [&](double q) {
    return d(static_cast<Eigen::Index>(std::floor(q * static_cast<double>(d.size() - 1))));
  };
  s.mean = d.mean();
  s.median = at(0.5);
  s.p90 = at(0.9);
  s.max = d(d.size() - 1);
  return s;
}

RegistrationResult register_to_target(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F,
                                      const RegistrationTarget& target,
                                      const RegistrationLandmarks& landmarks,
                                      const RegistrationOptions& options) {
  const auto start = Clock::now();
  check_options(options);
  require(V.cols() == 3 && V.rows() > 0, "the source must be #V x 3 with #V > 0");
  for (Eigen::Index i = 0; i < V.rows(); ++i)
    require(V.row(i).allFinite(), "source vertex " + std::to_string(i) + " is not finite");
  require(F.cols() == 3 && F.rows() > 0, "the source must have faces (#F x 3)");
  require(F.minCoeff() >= 0 && F.maxCoeff() < V.rows(), "a source face uses a vertex out of range");
  require(target.points.rows() > 0 && target.diagonal > 0, "the target is empty (make_registration_target)");
  const LandmarkPoints points = landmark_points(V, F, landmarks, options.landmark_weight);

  const CorrespondenceRules rules = correspondence_rules(options, target.diagonal);

  RegistrationResult result;
  RegistrationReport& report = result.report;
  report.target_diagonal = target.diagonal;
  {
    const ScopedTimer timer(report.prealign_ms);
    if (options.prealignment != Prealignment::None) {
      const auto aligned = registration_detail::prealign(V, F, target, points,
                                                         options.prealignment == Prealignment::Similarity,
                                                         options.prealign_rounds, rules);
      report.prealignment = aligned.transform;
      report.prealign_rounds = aligned.rounds;
    }
  }
  const Eigen::MatrixXd V0 = report.prealignment.apply(V);

  const Eigen::VectorXd areas = relative_vertex_areas(V0, F);

  const Eigen::Index n = V.rows(), nb = landmarks.faces.size();
  const ArapSoftConstraints soft = soft_points(n, landmarks, points, data_weight(options, 0));
  ArapOptions arap_options;
  arap_options.method = options.method;
  ArapData data = timed(report.precompute_ms,
                        [&] { return arap_precompute(V0, F, Eigen::VectorXi(0), soft, arap_options); });

  Eigen::MatrixXd U = V0;
  report.initial_distance = distance_statistics(U, target);
  const VertexFaces around = vertex_faces(F, n);
  const Eigen::MatrixXd no_fixed(0, 3);
  Eigen::MatrixXd soft_targets(n + nb, 3);
  soft_targets.bottomRows(nb) = points.target.bottomRows(nb);
  // Each target point spreads a unit of weight over its face's corners: #P / #V per vertex on average. Scaled
  // by #V / #P, the backward pulls weigh backward_weight times the forward ones whatever the density.
  const double backward_share =
      options.backward_weight * static_cast<double>(n) / static_cast<double>(target.points.rows());
  Eigen::VectorXd W;
  Eigen::MatrixXd T;
  for (int stage = 0; stage < options.stages; ++stage) {
    const double w_s = data_weight(options, stage);
    double previous_mean = -1;
    for (int round = 0; round < options.rounds_per_stage; ++round) {
      RegistrationRound r;
      r.stage = stage;
      r.round = round;
      r.data_weight = w_s;
      VertexPulls forward, backward;
      {
        const ScopedTimer timer(r.closest_ms);
        const Eigen::MatrixXd NU = area_weighted_vertex_normals(U, F);
        forward = registration_detail::forward_pulls(U, NU, target, rules);
        if (options.backward_weight > 0)
          backward = registration_detail::backward_pulls(U, NU, F, around, target, rules);
        combine(forward, backward, backward_share, w_s, areas, landmarks, points, U, W, T);
      }
      r.mean_distance = forward.mean_distance;
      r.median_distance = forward.median_distance;
      r.forward_used = forward.used;
      r.backward_used = backward.used;
      {
        const ScopedTimer timer(r.factor_ms);
        arap_set_soft_weights(data, W, soft.face_weights);
      }
      soft_targets.topRows(n) = T;
      const ArapReport solved =
          timed(r.solve_ms, [&] { return arap_solve(data, no_fixed, soft_targets, U, options.solve); });
      r.solver_iterations = solved.iterations;
      r.energy = solved.energies.empty() ? solved.initial_energy : solved.energies.back();
      report.closest_ms += r.closest_ms;
      report.factor_ms += r.factor_ms;
      report.solve_ms += r.solve_ms;
      report.rounds.push_back(r);
      if (options.on_round) options.on_round(r);
      report.stopped = options.on_round_shape && !options.on_round_shape(r, U);
      if (report.stopped) break;
      const bool settled = previous_mean >= 0 && std::abs(previous_mean - r.mean_distance) <=
                                                     options.stage_tolerance * previous_mean;
      previous_mean = r.mean_distance;
      if (settled) break;
    }
    if (report.stopped) break;
  }
  report.final_distance = distance_statistics(U, target);
  result.U = std::move(U);
  report.total_ms = ms_since(start);
  return result;
}

} // namespace iarap
