#include "iarap/param/param_options.h"

#include "iarap/core/errors.h"

#include <initializer_list>
#include <string>
#include <unordered_map>

namespace iarap {

namespace {

// The option whose name is `name`; else InputError "unknown <what> '<name>'; expected <expected>".
template <typename Option>
Option parse_named(const std::string& name, std::initializer_list<Option> options,
                   std::string (*name_of)(Option), const char* what, const char* expected) {
  for (Option option : options)
    if (name == name_of(option)) return option;
  throw InputError(std::string("unknown ") + what + " '" + name + "'; expected " + expected);
}

} // namespace

void check_uv_pins(const UvPins& pins, Eigen::Index num_vertices) {
  if (pins.uv.rows() != pins.vertices.size() || (pins.uv.size() > 0 && pins.uv.cols() != 2))
    throw InputError(
        "UV pins need one row of 2 positions per vertex: " + std::to_string(pins.vertices.size()) +
        " vertices, positions " + std::to_string(pins.uv.rows()) + " x " + std::to_string(pins.uv.cols()));
  std::unordered_map<int, Eigen::Index> seen;
  for (Eigen::Index p = 0; p < pins.size(); ++p) {
    const int v = pins.vertices(p);
    const std::string pin = "pin " + std::to_string(p) + " (vertex " + std::to_string(v) + ")";
    if (v < 0 || v >= num_vertices)
      throw InputError(pin + " is not a vertex; the mesh has " + std::to_string(num_vertices));
    if (!pins.uv.row(p).allFinite()) throw InputError(pin + " has a non-finite UV position");
    const auto [it, inserted] = seen.emplace(v, p);
    if (!inserted) throw InputError(pin + " pins the vertex of pin " + std::to_string(it->second) + " again");
  }
}

double default_barrier_weight(ParamEnergy energy) {
  return energy == ParamEnergy::Triangle ? 1e-2 : 1e-1;
}

std::string param_energy_name(ParamEnergy energy) {
  switch (energy) {
  case ParamEnergy::Triangle:
    return "triangle";
  case ParamEnergy::Arap:
    return "arap";
  case ParamEnergy::Iarap:
    return "iarap";
  }
  return "unknown";
}

ParamEnergy parse_param_energy(const std::string& name) {
  return parse_named(name, {ParamEnergy::Triangle, ParamEnergy::Arap, ParamEnergy::Iarap}, param_energy_name,
                     "energy", "triangle, arap or iarap");
}

ArapSolveOptions default_param_solve_options() {
  ArapSolveOptions options;
  options.max_iterations = 100;
  return options;
}

ParamInit default_param_init(ParamBoundary boundary) {
  return boundary == ParamBoundary::Circle ? ParamInit::Harmonic : ParamInit::Lscm;
}

std::string param_init_name(ParamInit init) {
  switch (init) {
  case ParamInit::Lscm:
    return "lscm";
  case ParamInit::Tutte:
    return "tutte";
  case ParamInit::Harmonic:
    return "harmonic";
  }
  return "unknown";
}

ParamInit parse_param_init(const std::string& name) {
  return parse_named(name, {ParamInit::Lscm, ParamInit::Tutte, ParamInit::Harmonic}, param_init_name,
                     "initial map", "lscm, tutte or harmonic");
}

std::string param_boundary_name(ParamBoundary boundary) {
  return boundary == ParamBoundary::Free ? "free" : "circle";
}

ParamBoundary parse_param_boundary(const std::string& name) {
  return parse_named(name, {ParamBoundary::Free, ParamBoundary::Circle}, param_boundary_name, "boundary",
                     "free or circle");
}

} // namespace iarap
