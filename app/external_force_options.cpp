#include "external_force_options.h"

#include "number_validators.h"

#include "iarap/core/errors.h"
#include "iarap/dynamics/simulation.h"
#include "iarap/mesh/connected_components.h"
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

Eigen::MatrixXd scaled_forces(const ExternalForceArguments& args, const Eigen::MatrixXd& V_scaled,
                              const Eigen::MatrixXi& F, ArapMethod method, double s,
                              const Eigen::MatrixXd& file_forces) {
  Eigen::MatrixXd f = Eigen::MatrixXd::Zero(V_scaled.rows(), 3);
  if (!args.gravity.empty())
    f = gravity_forces(arap_vertex_masses(V_scaled, F, method, args.density * s * s),
                       args.gravity_vector() / s);
  if (file_forces.rows() > 0) f += file_forces / s;
  return f;
}

void require_held_components(const Eigen::MatrixXi& F, int num_vertices, const Eigen::VectorXi& fixed,
                             const Eigen::VectorXi& soft_vertices, const Eigen::VectorXi& soft_faces) {
  int count = 0;
  const Eigen::VectorXi component = vertex_components(F, num_vertices, &count);
  std::vector<char> held(static_cast<size_t>(count), 0);
  for (Eigen::Index k = 0; k < fixed.size(); ++k) held[static_cast<size_t>(component(fixed(k)))] = 1;
  for (Eigen::Index k = 0; k < soft_vertices.size(); ++k)
    held[static_cast<size_t>(component(soft_vertices(k)))] = 1;
  for (Eigen::Index k = 0; k < soft_faces.size(); ++k)
    held[static_cast<size_t>(component(F(soft_faces(k), 0)))] = 1;
  std::vector<int> size(static_cast<size_t>(count), 0), first(static_cast<size_t>(count), -1);
  for (int v = 0; v < num_vertices; ++v) {
    const auto c = static_cast<size_t>(component(v));
    if (first[c] < 0) first[c] = v;
    ++size[c];
  }
  for (int c = 0; c < count; ++c) {
    const auto k = static_cast<size_t>(c);
    if (held[k] || size[k] < 2) continue; // a vertex used by no face carries no force's work
    throw InputError("connected component " + std::to_string(c) + " (" + std::to_string(size[k]) +
                     " vertices, e.g. vertex " + std::to_string(first[k]) +
                     ") has no constrained vertex: under --gravity / --forces a free body has no static "
                     "equilibrium; fix a vertex of it (or run `iarap simulate` for its motion)");
  }
}

} // namespace iarap::cli
