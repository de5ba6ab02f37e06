#include "iarap/dynamics/simulation.h"

#include "iarap/core/errors.h"
#include "iarap/mesh/normalize_scale.h"
#include "iarap/solver/arap.h"
#include "iarap/solver/solve_option_fields.h"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <sstream>
#include <string>

namespace iarap {

namespace {

void check_options(const SimulationOptions& options, Eigen::Index n) {
  if (!(std::isfinite(options.dt) && options.dt > 0))
    throw InputError("simulation: dt must be finite and > 0, got " + std::to_string(options.dt));
  if (!(options.damping >= 0 && options.damping < 1))
    throw InputError("simulation: damping must be in [0, 1), got " + std::to_string(options.damping));
  if (!options.gravity.allFinite()) throw InputError("simulation: gravity must be finite");
  if (options.arap.planar)
    throw InputError("simulation: ArapOptions::planar is not supported (a simulation moves in 3D)");
  if (options.forces.size() == 0) return;
  if (options.forces.rows() != n || options.forces.cols() != 3)
    throw InputError("simulation: forces must be " + std::to_string(n) + " x 3, got " +
                     std::to_string(options.forces.rows()) + " x " + std::to_string(options.forces.cols()));
  for (Eigen::Index r = 0; r < n; ++r)
    if (!options.forces.row(r).allFinite())
      throw InputError("simulation: forces row " + std::to_string(r) + " is not finite");
}

// The range of time steps that double precision can carry. The inertia term weighs the free vertices with
// W_i = m_i / (2 h^2): the solver needs every W_i to be a normal number (a weight that underflows to 0 or to
// a subnormal leaves a free body without inertia), and the system's diagonal 2 W_i = m_i / h^2, its
// right-hand side 2 W_i x_pred,i and the inertia energy W_i |x_i - x_pred,i|^2 to stay finite for positions
// and moves up to D = max(bounding-box diagonal, largest |V_i|). With m_min, m_max the extreme masses of
// the free vertices that holds for
//   h_min = sqrt(m_max) max(1, D) / sqrt(DBL_MAX) <= h <= h_max = sqrt(m_min / 2) / sqrt(DBL_MIN),
// computed through square roots so that neither bound over- or underflows on the way. Outside it the
// solver would refuse "soft vertex [0] has weight inf", naming a constraint the caller never gave.
void check_time_step(double dt, const Eigen::VectorXd& masses, const Eigen::VectorXi& inertial,
                     const Eigen::MatrixXd& V) {
  if (inertial.size() == 0) return; // no free vertex with mass: dt weighs nothing
  const double D =
      std::max((V.colwise().maxCoeff() - V.colwise().minCoeff()).norm(), V.rowwise().norm().maxCoeff());
  if (!std::isfinite(D)) return; // arap_precompute names the vertex
  double m_min = masses(inertial(0)), m_max = m_min;
  for (Eigen::Index i = 1; i < inertial.size(); ++i) {
    m_min = std::min(m_min, masses(inertial(i)));
    m_max = std::max(m_max, masses(inertial(i)));
  }
  const double h_min = std::sqrt(m_max) * std::max(1.0, D) / std::sqrt(DBL_MAX);
  const double h_max = std::sqrt(m_min / 2) / std::sqrt(DBL_MIN);
  if (dt >= h_min && dt <= h_max) return;
  std::ostringstream message;
  message.precision(3);
  message << "simulation: dt = " << dt << " is too " << (dt < h_min ? "small" : "large")
          << ": the inertia weights m_i / (2 dt^2) of the free vertices (masses " << m_min << " to " << m_max;
  if (D > 1) message << ", mesh size " << D; // below 1 the size does not enter the bound
  message << ") would " << (dt < h_min ? "overflow" : "underflow")
          << " in double precision; on this mesh dt must be in [" << h_min << ", " << h_max << "]";
  throw InputError(message.str());
}

// The inertia term as soft vertices (W_i = m_i / (2 h^2) at every free vertex with mass) ahead of the
// caller's soft points.
ArapSoftConstraints with_inertia(const ArapSoftConstraints& soft, const Eigen::VectorXi& inertial,
                                 const Eigen::VectorXd& masses, double dt) {
  ArapSoftConstraints all = soft;
  const Eigen::Index k = inertial.size(), s = soft.vertices.size();
  all.vertices.resize(k + s);
  all.vertex_weights.resize(k + s);
  for (Eigen::Index i = 0; i < k; ++i) {
    all.vertices(i) = inertial(i);
    all.vertex_weights(i) = masses(inertial(i)) / (2.0 * dt * dt);
  }
  all.vertices.tail(s) = soft.vertices;
  all.vertex_weights.tail(s) = soft.vertex_weights;
  return all;
}

} // namespace

Simulation::Simulation(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, const Eigen::VectorXi& fixed,
                       const SimulationOptions& options, const ArapSoftConstraints& soft)
    : options_(options) {
  if (V.cols() != 3)
    throw InputError("simulation: V must be #V x 3, got " + std::to_string(V.rows()) + " x " +
                     std::to_string(V.cols()));
  check_options(options, V.rows());
  // The solves run on V / s, s a power of two that brings the coordinates near 1 (exact: the results are
  // the same numbers, in the input's units, for a mesh in millimetres or in kilometres). Masses do not
  // change with it; lengths, forces and solve options measured in mesh units are divided by s.
  s_ = normalizing_scale(V);
  scale_length_options(options_.solve, s_);
  masses_ = arap_vertex_masses(V, F, options.arap.method, options.density);
  forces_ = gravity_forces(masses_, options.gravity);
  if (options.forces.size() > 0) forces_ += options.forces;
  is_fixed_.assign(static_cast<size_t>(V.rows()), 0);
  for (Eigen::Index k = 0; k < fixed.size(); ++k)
    if (fixed(k) >= 0 && fixed(k) < V.rows()) is_fixed_[static_cast<size_t>(fixed(k))] = 1;
  std::vector<int> inertial;
  for (Eigen::Index v = 0; v < V.rows(); ++v)
    if (!is_fixed_[static_cast<size_t>(v)] && masses_(v) > 0) inertial.push_back(static_cast<int>(v));
  inertial_ = Eigen::Map<const Eigen::VectorXi>(inertial.data(), static_cast<Eigen::Index>(inertial.size()));
  const Eigen::MatrixXd V_scaled = V / s_;
  check_time_step(options.dt, masses_, inertial_, V_scaled);
  data_ =
      arap_precompute(V_scaled, F, fixed, with_inertia(soft, inertial_, masses_, options.dt), options.arap);
  X_ = V;
  velocity_ = Eigen::MatrixXd::Zero(V.rows(), 3);
  targets_.resize(fixed.size(), 3);
  for (Eigen::Index k = 0; k < fixed.size(); ++k) targets_.row(k) = V.row(fixed(k));
  soft_targets_ = Eigen::MatrixXd(0, 3);
}

SimulationStepReport Simulation::step() {
  if (soft_targets_.rows() != data_.soft.size() - inertial_.size())
    throw InputError("simulation: the soft constraints need targets: step(targets, soft_targets)");
  return step(Eigen::MatrixXd(targets_), Eigen::MatrixXd(soft_targets_));
}

SimulationStepReport Simulation::step(const Eigen::MatrixXd& targets, const Eigen::MatrixXd& soft_targets) {
  const double h = options_.dt;
  const Eigen::Index k = inertial_.size();
  const Eigen::Index user_soft = data_.soft.size() - k;
  if (soft_targets.rows() != user_soft || soft_targets.cols() != 3)
    throw InputError("simulation: soft targets must be " + std::to_string(user_soft) + " x 3, got " +
                     std::to_string(soft_targets.rows()) + " x " + std::to_string(soft_targets.cols()));
  // x_pred = x_n + h v_n: the inertia's targets and the warm start (on the mesh divided by s).
  Eigen::MatrixXd U = (X_ + h * velocity_) / s_;
  Eigen::MatrixXd all_targets(k + user_soft, 3);
  for (Eigen::Index i = 0; i < k; ++i) all_targets.row(i) = U.row(inertial_(i));
  all_targets.bottomRows(user_soft) = soft_targets / s_;
  ArapSolveOptions solve = options_.solve;
  solve.forces = forces_ / s_;
  SimulationStepReport out;
  out.solve = arap_solve(data_, targets / s_, all_targets, U, solve); // throws before any change
  rescale_report(out.solve, s_);
  U *= s_;
  velocity_ = (U - X_) / h;
  for (Eigen::Index v = 0; v < U.rows(); ++v)
    if (!is_fixed_[static_cast<size_t>(v)]) velocity_.row(v) *= 1.0 - options_.damping;
  X_ = std::move(U);
  targets_ = targets;
  soft_targets_ = soft_targets;
  ++steps_;
  time_ = steps_ * h;
  out.step = steps_;
  out.time = time_;
  out.kinetic_energy = kinetic_energy();
  return out;
}

void Simulation::set_velocities(const Eigen::MatrixXd& velocities) {
  if (velocities.rows() != X_.rows() || velocities.cols() != 3)
    throw InputError("simulation: velocities must be " + std::to_string(X_.rows()) + " x 3, got " +
                     std::to_string(velocities.rows()) + " x " + std::to_string(velocities.cols()));
  for (Eigen::Index r = 0; r < velocities.rows(); ++r)
    if (!velocities.row(r).allFinite())
      throw InputError("simulation: velocities row " + std::to_string(r) + " is not finite");
  velocity_ = velocities;
}

Eigen::Vector3d Simulation::momentum() const {
  return (velocity_.transpose() * masses_);
}

double Simulation::kinetic_energy() const {
  return 0.5 * masses_.dot(velocity_.rowwise().squaredNorm());
}

double Simulation::elastic_energy() const {
  return arap_energy(data_, X_ / s_) * (s_ * s_);
}

double Simulation::potential_energy() const {
  return forces_.cwiseProduct(data_.V * s_).sum() - forces_.cwiseProduct(X_).sum();
}

} // namespace iarap
