#include "external_force_options.h"

#include "number_validators.h"

#include "iarap/core/errors.h"
#include "iarap/scene/read_forces.h"

namespace iarap::cli {

void add_external_force_options(CLI::App& command, ExternalForceArguments& args) {
  command
      .add_option(
          "--gravity", args.gravity,
          "Gravity GX GY GZ in mesh units / time^2: a force m_i g on each vertex, m_i = density x the "
          "area of its lumped cell (intrinsic Voronoi for iarap, Voronoi for arap and spokes-rims)")
      ->expected(3)
      ->check(finite_number);
  command
      .add_option("--forces", args.forces,
                  "Per-vertex forces file: 'index fx fy fz' per line (mass x mesh units / time^2; lines of "
                  "one vertex add up)")
      ->check(CLI::ExistingFile);
  command.add_option("--density", args.density, "Surface density: mass = density x area")
      ->check(finite_positive)
      ->capture_default_str();
}

Eigen::MatrixXd file_forces(const ExternalForceArguments& args, int num_vertices) {
  if (args.forces.empty()) return Eigen::MatrixXd();
  return read_forces(args.forces, num_vertices);
}

} // namespace iarap::cli
