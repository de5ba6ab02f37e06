// Simulation (implicit-Euler dynamics of the ARAP energy, iarap/dynamics/simulation.h) and vertex_masses.
// Steps run without the GIL; a mutex keeps two Python threads off one simulation at a time.
#include "bindings.h"
#include "numpy_arrays.h"
#include "solve_option_keywords.h"

#include "iarap/core/errors.h"
#include "iarap/dynamics/simulation.h"
#include "iarap/dynamics/simulation_report_fields.h"

#include <memory>
#include <mutex>

namespace iarap::python {
namespace {

class PySimulation {
public:
  PySimulation(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, const Eigen::VectorXi& fixed,
               const SimulationOptions& options)
      : sim_(V, F, fixed, options) {}

  template <typename Function> auto with(Function&& f) {
    std::lock_guard<std::mutex> lock(mutex_);
    return f(sim_);
  }

private:
  std::mutex mutex_;
  Simulation sim_;
};

// Three finite numbers (a sequence or an array of 3) as a vector; InputError naming `name` otherwise.
// Simulation's parameters: the mesh and fixed vertices, the dynamics, then each step's solve options
// (keyword-only, defaults SimulationOptions::default_step_options()).
KeywordSignature simulation_signature() {
  std::vector<Parameter> parameters = {{"V", "npt.ArrayLike", py::object(), false},
                                       {"F", "npt.ArrayLike", py::object(), false},
                                       {"fixed", "npt.ArrayLike | None", py::none(), false},
                                       {"dt", "float", py::object(), true},
                                       {"method", "str", py::str("iarap"), true},
                                       {"gravity", "npt.ArrayLike", py::make_tuple(0.0, 0.0, 0.0), true},
                                       {"damping", "float", py::float_(0.0), true},
                                       {"density", "float", py::float_(1.0), true},
                                       {"forces", "npt.ArrayLike | None", py::none(), true},
                                       {"refine_boundary", "bool", py::bool_(true), true}};
  for (Parameter& p : solve_option_parameters(SimulationOptions::default_step_options(), 0))
    parameters.push_back(std::move(p));
  return KeywordSignature("__init__", std::move(parameters), "None");
}

std::unique_ptr<PySimulation> make_simulation(const BoundArguments& arguments) {
  const py::object &V = arguments["V"], &F = arguments["F"], &fixed = arguments["fixed"],
                   &gravity = arguments["gravity"], &forces = arguments["forces"];
  const auto dt = arguments.as<double>("dt"), damping = arguments.as<double>("damping"),
             density = arguments.as<double>("density");
  const auto method = arguments.as<std::string>("method");
  const auto refine_boundary = arguments.as<bool>("refine_boundary");
  const Eigen::MatrixXd positions = to_points(V, "V");
  const Eigen::MatrixXi faces = to_faces(F, "F", positions.rows());
  const Eigen::VectorXi constrained =
      fixed.is_none() ? Eigen::VectorXi(0) : to_indices(fixed, "fixed", positions.rows());
  SimulationOptions options;
  options.arap.method = parse_arap_method(method);
  options.arap.intrinsic.refine_boundary = refine_boundary;
  options.dt = dt;
  options.damping = damping;
  options.density = density;
  options.gravity = to_vector3(gravity, "gravity");
  if (!forces.is_none()) options.forces = to_points(forces, "forces", true, positions.rows(), "#V");
  set_solve_options(options.solve, arguments);
  py::gil_scoped_release release;
  return std::make_unique<PySimulation>(positions, faces, constrained, options);
}

py::dict step_py(PySimulation& sim, const py::object& targets) {
  const Eigen::Index fixed_count = sim.with([](Simulation& s) { return s.data().fixed.size(); });
  SimulationStepReport r;
  if (targets.is_none()) {
    py::gil_scoped_release release;
    r = sim.with([](Simulation& s) { return s.step(); });
  } else {
    const Eigen::MatrixXd rows = to_points(targets, "targets", true, fixed_count, "#fixed");
    py::gil_scoped_release release;
    r = sim.with([&](Simulation& s) { return s.step(rows, Eigen::MatrixXd(0, 3)); });
  }
  py::dict d;
  visit_simulation_step_report(r,
                               [&d](const char* name, const auto& value) { d[name] = report_value(value); });
  return d;
}

// A read-only property of the simulation: f(simulation) converted by to_numpy or as it is.
template <typename Function> auto getter(Function f) {
  return [f](PySimulation& s) { return s.with([&](Simulation& sim) { return f(sim); }); };
}

} // namespace

void bind_dynamics(py::module_& m) {
  m.def(
      "vertex_masses",
      [](const py::object& V, const py::object& F, const std::string& method, double density) {
        const Eigen::MatrixXd positions = to_points(V, "V");
        const Eigen::MatrixXi faces = to_faces(F, "F", positions.rows());
        const ArapMethod kind = parse_arap_method(method);
        py::gil_scoped_release release;
        const Eigen::VectorXd masses = arap_vertex_masses(positions, faces, kind, density);
        py::gil_scoped_acquire acquire;
        return to_numpy(masses);
      },
      py::arg("V"), py::arg("F"), py::arg("method") = "iarap", py::arg("density") = 1.0,
      R"(float64 (#V,): lumped masses m_i = density x the area of vertex i's mixed Voronoi cell, on the
intrinsic Delaunay triangulation for "iarap", on the input mesh for "arap" and "spokes-rims".)");

  py::class_<PySimulation> simulation(m, "Simulation", R"(Implicit-Euler dynamics of the ARAP elastic energy.

Each step minimizes sum_i m_i / (2 dt^2) |y_i - x_i - dt v_i|^2 + E_ARAP(y) - f . (y - V) over y by the
local/global solver (the inertia is a soft constraint on every free vertex), then sets
v = (1 - damping) (y - x) / dt at the free vertices and x = y. Units: positions in mesh units, masses density x
area, gravity in mesh units / time^2, energies in mass x (mesh units / time)^2 with E_ARAP at stiffness 1.

    sim = iarap.Simulation(V, F, fixed=bottom, dt=0.1, gravity=(0, -1, 0), damping=0.1)
    for _ in range(100):
        report = sim.step()          # the fixed vertices stay at their last targets (at first: rest)
    sim.positions, sim.velocities, sim.kinetic_energy, sim.elastic_energy)");
  const auto signature = std::make_shared<const KeywordSignature>(simulation_signature());
  {
    py::options options;
    options.disable_function_signatures();
    simulation.def(py::init([signature](const py::args& args, const py::kwargs& kwargs) {
                     return make_simulation(signature->bind(args, kwargs));
                   }),
                   (signature->text() + R"(

V (#V, 3), F (#F, 3), fixed: vertex indices held at their targets (None: a free body). dt > 0;
damping in [0, 1); density > 0; gravity (3,); forces (#V, 3) further constant forces. Each step's solve
(as ARAP.solve):
)" + solve_option_docs() +
                    "Raises InputError for a bad value, naming it.")
                       .c_str());
  }
  simulation
      .def("step", &step_py, py::arg("targets") = py::none(),
           "One step to time + dt; targets (#fixed, 3) where the fixed vertices are then (None: where they "
           "were). Returns {step, time, kinetic_energy, elastic_energy, potential_energy, total_energy} and "
           "the step's solve report as ARAP.report has it (iterations, converged, stop_reason, energies, "
           "gradient_norms, times, ...).")
      .def_property_readonly("positions", getter([](Simulation& s) { return to_numpy(s.positions()); }),
                             "float64 (#V, 3): the positions now.")
      .def_property(
          "velocities", getter([](Simulation& s) { return to_numpy(s.velocities()); }),
          [](PySimulation& s, const py::object& v) {
            const Eigen::Index n = s.with([](Simulation& sim) { return sim.positions().rows(); });
            const Eigen::MatrixXd rows = to_points(v, "velocities", true, n, "#V");
            s.with([&](Simulation& sim) { sim.set_velocities(rows); });
          },
          "float64 (#V, 3): the velocities now (assign an initial velocity).")
      .def_property_readonly("masses", getter([](Simulation& s) { return to_numpy(s.masses()); }),
                             "float64 (#V,): the lumped masses.")
      .def_property_readonly("forces", getter([](Simulation& s) { return to_numpy(s.forces()); }),
                             "float64 (#V, 3): gravity's forces plus `forces`.")
      .def_property_readonly("momentum",
                             getter([](Simulation& s) { return to_numpy(Eigen::VectorXd(s.momentum())); }),
                             "float64 (3,): sum_i m_i v_i.")
      .def_property_readonly("kinetic_energy", getter([](Simulation& s) { return s.kinetic_energy(); }),
                             "sum_i m_i |v_i|^2 / 2.")
      .def_property_readonly("elastic_energy", getter([](Simulation& s) { return s.elastic_energy(); }),
                             "E_ARAP of the positions.")
      .def_property_readonly("potential_energy", getter([](Simulation& s) { return s.potential_energy(); }),
                             "-f . (positions - V).")
      .def_property_readonly("time", getter([](Simulation& s) { return s.time(); }), "steps x dt.")
      .def_property_readonly("steps", getter([](Simulation& s) { return s.steps(); }), "Steps taken.");
}

} // namespace iarap::python
