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

} // namespace iarap::cli
