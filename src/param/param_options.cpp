#include "iarap/param/param_options.h"

#include "iarap/core/errors.h"

namespace iarap {

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
  for (ParamEnergy energy : {ParamEnergy::Triangle, ParamEnergy::Arap, ParamEnergy::Iarap})
    if (name == param_energy_name(energy)) return energy;
  throw InputError("unknown energy '" + name + "'; expected triangle, arap or iarap");
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
  for (ParamInit init : {ParamInit::Lscm, ParamInit::Tutte, ParamInit::Harmonic})
    if (name == param_init_name(init)) return init;
  throw InputError("unknown initial map '" + name + "'; expected lscm, tutte or harmonic");
}

std::string param_boundary_name(ParamBoundary boundary) {
  return boundary == ParamBoundary::Free ? "free" : "circle";
}

ParamBoundary parse_param_boundary(const std::string& name) {
  for (ParamBoundary boundary : {ParamBoundary::Free, ParamBoundary::Circle})
    if (name == param_boundary_name(boundary)) return boundary;
  throw InputError("unknown boundary '" + name + "'; expected free or circle");
}

} // namespace iarap
