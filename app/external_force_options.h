// The options of external forces shared by `iarap deform` (statics) and `iarap simulate` (dynamics):
// --gravity GX GY GZ, --forces FILE (per-vertex forces, iarap/scene/read_forces.h) and --density.
#pragma once
#include "iarap/solver/arap_types.h"

#include <CLI/CLI.hpp>
#include <Eigen/Core>

#include <string>
#include <vector>

namespace iarap::cli {

struct ExternalForceArguments {
  std::vector<double> gravity; // empty, or GX GY GZ in mesh units / time^2
  std::string forces;          // a forces file, or empty
  double density = 1.0;        // surface density: mass = density x area
  bool any() const { return !gravity.empty() || !forces.empty(); }
  Eigen::Vector3d gravity_vector() const {
    return gravity.empty() ? Eigen::Vector3d::Zero() : Eigen::Vector3d(gravity[0], gravity[1], gravity[2]);
  }
};

void add_external_force_options(CLI::App& command, ExternalForceArguments& args);

// The forces file's #V x 3 forces (file units), or a 0 x 0 matrix without --forces.
Eigen::MatrixXd file_forces(const ExternalForceArguments& args, int num_vertices);

// The forces of a solve on the mesh divided by s (V_scaled = V / s, a power of two): in those units a
// mass is density s^2 x area (the file's mass) and a force f / s, so that the minimizer is the file's
// divided by s and energies are the file's / s^2. m_i g / s + file forces / s.
Eigen::MatrixXd scaled_forces(const ExternalForceArguments& args, const Eigen::MatrixXd& V_scaled,
                              const Eigen::MatrixXi& F, ArapMethod method, double s,
                              const Eigen::MatrixXd& file_forces);

// Throws InputError when a connected component of (#V, F) has no fixed vertex and no soft point: under an
// external force a free body has no equilibrium.
void require_held_components(const Eigen::MatrixXi& F, int num_vertices, const Eigen::VectorXi& fixed,
                             const Eigen::VectorXi& soft_vertices, const Eigen::VectorXi& soft_faces);

} // namespace iarap::cli
