// Dynamics of the ARAP elastic energy (issue 32, item 4) and the lumped masses that go with each energy.
//
// Implicit Euler: with x_pred = x_n + h v_n each step minimizes
//
//   Phi(x) = sum_i m_i / (2 h^2) |x_i - x_pred,i|^2 + E_ARAP(x) - f . (x - V)
//
// over the free vertices (the fixed ones at their targets for t_{n+1}), by the local/global solver of
// arap_solve warm-started at x_pred (every accelerator applies). With a lumped mass matrix the inertia term
// is a soft vertex constraint on every free vertex, W_i = m_i / (2 h^2) with target x_pred,i
// (arap_soft_constraints.h): one numeric factorization of (L + M / h^2)_ff per time step h, new targets
// each step for free. Then v_{n+1} = (x_{n+1} - x_n) / h, scaled by (1 - damping) at the free vertices.
//
// Units: positions in mesh units, time in the unit of h, masses m_i = density x area of vertex i's cell
// (a surface density), forces in mass x mesh units / time^2 (gravity: f_i = m_i g, g in mesh units / time^2).
// E_ARAP is the elastic energy with stiffness 1 (mass / time^2): a denser or larger mesh sags more,
// roughly as density |g| size^2.
#pragma once
#include "iarap/solver/arap_types.h"

#include <Eigen/Core>

namespace iarap {

// Lumped masses m_i = density x area of vertex i's mixed Voronoi cell: on the intrinsic Delaunay
// triangulation for ArapMethod::Iarap (the partner of its Laplacian, mass_matrix.h "intrinsic"), on the
// input mesh for Arap and SpokesRims ("voronoi"). V #V x 3 (or #V x 2 in the plane). A vertex used by no
// face gets 0. Throws InputError for a density that is not finite and > 0, and as mass_matrix.
Eigen::VectorXd arap_vertex_masses(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, ArapMethod method,
                                   double density = 1.0);

// f_i = m_i g: #V x 3 forces of gravity g on the masses m. Throws InputError for a non-finite g.
Eigen::MatrixXd gravity_forces(const Eigen::VectorXd& masses, const Eigen::Vector3d& gravity);

struct SimulationOptions {
  ArapOptions arap; // the energy (planar is not supported: a simulation moves in 3D)
  // h > 0, finite, and within the range where the inertia weights m_i / (2 h^2) are normal doubles whose
  // terms stay finite: sqrt(m_max) max(1, D) / sqrt(DBL_MAX) <= h <= sqrt(m_min / 2) / sqrt(DBL_MIN), over
  // the free vertices' masses, D the larger of the bounding-box diagonal and the largest |V_i| (about
  // 1e-154 to 1e+153 for masses and sizes near 1). The constructor's InputError names dt and the range.
  double dt = 0.01;
  double density = 1.0; // surface density, > 0
  double damping = 0.0; // in [0, 1): v_{n+1} = (1 - damping) (x_{n+1} - x_n) / h at the free vertices
  Eigen::Vector3d gravity = Eigen::Vector3d::Zero();
  Eigen::MatrixXd forces; // #V x 3 further constant forces (0 x 0: none), added to gravity's
  // Iterations per step: the solver's options (their forces are ignored: the two fields above make them).
  // The default stops on the relative decrease 1e-10 of Phi, whose inertia term keeps it away from 0.
  ArapSolveOptions solve = default_step_options();

  static ArapSolveOptions default_step_options() {
    ArapSolveOptions options;
    options.max_iterations = 100;
    options.tolerance = 1e-10;
    return options;
  }
};

// What one step did: the step's own figures and the report of its solve (simulation_report_fields.h
// names them for the front-ends).
struct SimulationStepReport {
  int step = 0;              // 1 for the first step
  double time = 0;           // step x dt
  double kinetic_energy = 0; // sum_i m_i |v_i|^2 / 2 after the step (damped velocities)
  // The step's arap_solve: iterations, converged, stop_reason, energies (of Phi), times, ...; arap_energy is
  // E_ARAP(x_{n+1}), potential -f . (x_{n+1} - V) and penalty the inertia term (plus any soft points').
  ArapReport solve;
};

class Simulation {
public:
  // The rest mesh V (#V x 3), F, the fixed vertices (may be empty: then every component is held by its
  // inertia only) and soft constraints on top of the inertia (their targets go to step()). Starts at rest
  // (x = V, v = 0). Throws InputError for bad options (naming the field and value), bad fixed or soft sets
  // and meshes as arap_precompute, SolverError when the factorization fails.
  Simulation(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, const Eigen::VectorXi& fixed,
             const SimulationOptions& options, const ArapSoftConstraints& soft = {});

  // One step to t + dt with the fixed vertices at targets (#fixed x 3) and the soft points' targets
  // (soft.size() x 3). Throws InputError for a bad shape or a non-finite row (the state is then unchanged),
  // SolverError when the energy becomes non-finite.
  SimulationStepReport step(const Eigen::MatrixXd& targets, const Eigen::MatrixXd& soft_targets);
  // The same with the targets of the last step (at first: the fixed vertices' rest positions, and no soft
  // points).
  SimulationStepReport step();

  // #V x 3 velocities (finite; InputError otherwise), e.g. an initial velocity.
  void set_velocities(const Eigen::MatrixXd& velocities);

  const Eigen::MatrixXd& positions() const { return X_; }
  const Eigen::MatrixXd& velocities() const { return velocity_; }
  const Eigen::VectorXd& masses() const { return masses_; }
  const Eigen::MatrixXd& forces() const { return forces_; } // gravity's plus options.forces
  Eigen::Vector3d momentum() const;                         // sum_i m_i v_i
  double kinetic_energy() const;
  double elastic_energy() const; // E_ARAP(positions())
  double potential_energy() const;
  double time() const { return time_; }
  int steps() const { return steps_; }
  const ArapData& data() const { return data_; } // of the rest mesh divided by scale()
  double scale() const { return s_; }

private:
  SimulationOptions options_;
  Eigen::VectorXd masses_;
  Eigen::MatrixXd forces_, X_, velocity_, targets_, soft_targets_;
  Eigen::VectorXi inertial_; // the free vertices with mass, the soft vertices of the inertia term
  std::vector<char> is_fixed_;
  ArapData data_;  // of V / s_
  double s_ = 1.0; // normalizing_scale(V): the solves run on the mesh divided by it
  double time_ = 0;
  int steps_ = 0;
};

} // namespace iarap
