// `iarap simulate MESH`: implicit-Euler dynamics of the ARAP elastic energy (iarap/dynamics/simulation.h),
// the handles of a constraints or scenario file moving to their targets, written as numbered frames.
#include "command_registry.h"
#include "common/explain_error.h"
#include "common/json_text.h"
#include "external_force_options.h"
#include "iarap/jobs/soft_constraints.h"
#include "number_validators.h"
#include "solve_option_flags.h"
#include "solve_report_json.h"
#include "write_text_file.h"

#include "iarap/core/errors.h"
#include "iarap/core/threads.h"
#include "iarap/dynamics/simulation.h"
#include "iarap/dynamics/simulation_report_fields.h"
#include "iarap/io/read_mesh.h"
#include "iarap/io/write_mesh.h"
#include "iarap/mesh/validate.h"
#include "iarap/scene/read_constraints.h"
#include "iarap/scene/read_scenario.h"
#include "iarap/solver/arap.h"
#include "iarap/solver/solve_option_fields.h"

#include <nlohmann/json.hpp>

#include <cstdio>
#include <filesystem>
#include <iostream>
#include <unistd.h>

namespace iarap::cli {
namespace {

namespace fs = std::filesystem;

struct SimulateArguments {
  std::string mesh, constraints, scenario, method = "iarap", boundary = "refine", out_dir, format = "obj";
  double dt = 0, damping = 0;
  int steps = 0, every = 1, ramp = 0, threads = 0;
  ArapSolveOptions solve = SimulationOptions::default_step_options(); // each step's solve
  bool json = false, quiet = false;
  ExternalForceArguments forces;
};

// Where the handles are at a fraction alpha in [0, 1] of their motion: a scenario's rigid motions scaled
// (translation alpha t, rotation alpha x the angle about the same axis and centre), a constraints file's
// targets on the segment from the rest positions.
class HandlePath {
public:
  HandlePath(const SimulateArguments& args, const MeshData& mesh) : V_(mesh.V) {
    if (!args.scenario.empty()) {
      scenario_ = read_scenario(args.scenario);
      full_ = resolve_scenario(scenario_, V_);
      from_scenario_ = true;
    } else {
      full_ =
          read_constraints(args.constraints, static_cast<int>(V_.rows()), static_cast<int>(mesh.F.rows()));
    }
  }
  const ConstraintSet& full() const { return full_; }

  ConstraintSet at(double alpha, const Eigen::MatrixXi& F) const {
    if (from_scenario_) {
      Scenario scaled = scenario_;
      for (Handle& h : scaled.handles) {
        h.translation *= alpha;
        h.rotation_degrees *= alpha;
      }
      return resolve_scenario(scaled, V_);
    }
    ConstraintSet c = full_;
    for (Eigen::Index k = 0; k < c.fixed.size(); ++k)
      c.targets.row(k) = V_.row(c.fixed(k)) + alpha * (full_.targets.row(k) - V_.row(c.fixed(k)));
    SoftConstraintSet& s = c.soft;
    for (Eigen::Index k = 0; k < s.vertices.size(); ++k)
      s.vertex_targets.row(k) =
          V_.row(s.vertices(k)) + alpha * (s.vertex_targets.row(k) - V_.row(s.vertices(k)));
    for (Eigen::Index k = 0; k < s.faces.size(); ++k) {
      Eigen::RowVector3d rest = Eigen::RowVector3d::Zero();
      for (int j = 0; j < 3; ++j) rest += s.barycentric(k, j) * V_.row(F(s.faces(k), j));
      s.face_targets.row(k) = rest + alpha * (s.face_targets.row(k) - rest);
    }
    for (Eigen::Index k = 0; k < s.hard_faces.size(); ++k) {
      Eigen::RowVector3d rest = Eigen::RowVector3d::Zero();
      for (int j = 0; j < 3; ++j) rest += s.hard_barycentric(k, j) * V_.row(F(s.hard_faces(k), j));
      s.hard_targets.row(k) = rest + alpha * (s.hard_targets.row(k) - rest);
    }
    return c;
  }

private:
  Eigen::MatrixXd V_;
  Scenario scenario_;
  ConstraintSet full_;
  bool from_scenario_ = false;
};

// The frames go to a private folder inside the output folder and are moved in only when the whole run
// succeeded: a failed run leaves no frame of its own behind (each frame is also written atomically).
class FrameFolder {
public:
  FrameFolder(const std::string& dir, const std::string& format) : dir_(dir), format_(format) {
    std::error_code error;
    if (fs::exists(dir_, error) && !fs::is_directory(dir_, error))
      throw InputError(dir + ": --out-dir is a file, not a folder; refusing to write frames there");
    fs::create_directories(dir_, error);
    if (error) throw InputError(dir + ": cannot create the output folder: " + error.message());
    staging_ = dir_ / (".simulate-partial-" + std::to_string(::getpid()));
    fs::create_directories(staging_, error);
    if (error) throw InputError(dir + ": cannot write in the output folder: " + error.message());
  }
  ~FrameFolder() {
    std::error_code ignored;
    fs::remove_all(staging_, ignored); // empty after commit(); the partial frames after an error
  }
  FrameFolder(const FrameFolder&) = delete;
  FrameFolder& operator=(const FrameFolder&) = delete;

  std::string write(int step, const Eigen::MatrixXd& X, const Eigen::MatrixXi& F) {
    char name[32];
    std::snprintf(name, sizeof name, "frame_%06d.", step);
    const std::string file = name + format_;
    write_mesh((staging_ / file).string(), X, F);
    names_.push_back(file);
    return file;
  }

  void commit() {
    for (const std::string& name : names_) {
      std::error_code error;
      fs::rename(staging_ / name, dir_ / name, error);
      if (error) throw InputError((dir_ / name).string() + ": cannot move the frame in: " + error.message());
    }
  }

private:
  fs::path dir_, staging_;
  std::string format_;
  std::vector<std::string> names_;
};

// In the file's units: the simulation runs on the mesh divided by its normalizing scale itself.
SimulationOptions simulation_options(const SimulateArguments& args, const MeshData& mesh) {
  SimulationOptions options;
  options.arap.method = parse_arap_method(args.method);
  options.arap.intrinsic.refine_boundary = args.boundary == "refine";
  options.dt = args.dt;
  options.damping = args.damping;
  options.density = args.forces.density;
  options.gravity = args.forces.gravity_vector();
  options.forces = file_forces(args.forces, static_cast<int>(mesh.V.rows()));
  options.solve = args.solve;
  return options;
}

void run_simulate(const SimulateArguments& args) {
  if (args.constraints.empty() == args.scenario.empty())
    throw CLI::ValidationError("give exactly one of --constraints FILE and --scenario FILE");
  const MeshData mesh = read_mesh(args.mesh);
  const MeshReport check = check_mesh(mesh.V, mesh.F);
  if (!check.usable()) {
    std::string message = args.mesh + ": mesh not usable for ARAP:";
    for (const auto& error : check.errors) message += "\n  " + name_repair(error, deform_repair_flag);
    throw TopologyError(message + "\n(run `iarap info " + args.mesh + "` for the full report)");
  }
  const HandlePath path(args, mesh);
  set_thread_count(args.threads == 0 ? automatic_thread_count(static_cast<int>(mesh.V.rows()))
                                     : args.threads);
  const SimulationOptions options = simulation_options(args, mesh);
  std::optional<Simulation> sim;
  try {
    sim.emplace(mesh.V, mesh.F, path.full().fixed, options, soft_constraints_of(path.full().soft));
  } catch (const SolverError& e) {
    throw SolverError(explain_solver_error(e.what(), ErrorContext{args.mesh, false}));
  }
  FrameFolder frames(args.out_dir, args.format); // after every input check: a bad input writes nothing
  const int ramp = args.ramp > 0 ? args.ramp : args.steps;
  nlohmann::json steps = nlohmann::json::array(), names = nlohmann::json::array();
  names.push_back(frames.write(0, sim->positions(), mesh.F));
  for (int n = 1; n <= args.steps; ++n) {
    const ConstraintSet c = path.at(std::min(1.0, static_cast<double>(n) / ramp), mesh.F);
    SimulationStepReport r;
    try {
      r = sim->step(c.targets, soft_targets_of(c.soft));
    } catch (const HardPointConflict& e) {
      throw InputError(hard_point_conflict_message(e, c.soft));
    }
    nlohmann::json row;
    visit_simulation_step_report(r, [&row](const char* name, const auto& value) { row[name] = value; });
    steps.push_back(std::move(row));
    if (n % args.every == 0 || n == args.steps) {
      names.push_back(frames.write(n, sim->positions(), mesh.F));
      if (!args.quiet)
        std::cerr << "simulate: step " << n << "/" << args.steps << " t " << r.time << " kinetic "
                  << r.kinetic_energy << " elastic " << r.solve.arap_energy << " (" << r.solve.iterations
                  << " iterations)\n";
    }
  }
  nlohmann::json j;
  j["input"] = args.mesh;
  j["method"] = args.method;
  j["vertices"] = mesh.V.rows();
  j["faces"] = mesh.F.rows();
  j["constrained"] = path.full().fixed.size();
  j["soft"] = path.full().soft.size();
  j["dt"] = args.dt;
  j["steps"] = args.steps;
  j["ramp_steps"] = ramp;
  j["damping"] = args.damping;
  j["options"] = solve_options_json(args.solve);
  j["density"] = args.forces.density;
  j["gravity"] = args.forces.gravity.empty() ? std::vector<double>{0.0, 0.0, 0.0} : args.forces.gravity;
  j["forces"] = args.forces.forces;
  j["mass"] = sim->masses().sum(); // file units: density x area
  j["bbox_diagonal"] = check.bbox_diagonal;
  j["max_displacement"] = (sim->positions() - mesh.V).rowwise().norm().maxCoeff();
  j["frames"] = names;
  j["per_step"] = steps;
  frames.commit();
  const std::string text = json_text(j);
  write_text_file((fs::path(args.out_dir) / "simulation.json").string(), text);
  if (args.json) std::cout << text;
  if (!args.quiet) std::cerr << "simulate: wrote " << names.size() << " frames to " << args.out_dir << "\n";
}

const CLI::Validator damping_fraction(
    [](const std::string& text) -> std::string {
      double value = 0;
      if (!CLI::detail::lexical_cast(text, value)) return "'" + text + "' is not a number";
      if (!(value >= 0 && value < 1)) return "'" + text + "' must be a number in [0, 1)";
      return {};
    },
    "NUMBER in [0, 1)");

void add_solver_options(CLI::App& sub, SimulateArguments& args) {
  sub.add_option("--method", args.method, "Energy: arap, spokes-rims or iarap")
      ->check(CLI::IsMember({"arap", "spokes-rims", "iarap"}))
      ->capture_default_str();
  sub.add_option("--boundary", args.boundary,
                 "iARAP on meshes with boundary: 'refine' or 'paper' (see deform)")
      ->check(CLI::IsMember({"paper", "refine"}))
      ->capture_default_str();
  add_solve_option_flags(sub, args.solve);
  sub.add_option("--threads", args.threads, "Threads for the parallel loops; 0 = all hardware threads")
      ->check(CLI::Range(0, 4096))
      ->capture_default_str();
}

const bool simulate_command_registered = register_command(
    {"simulate", [](CLI::App& app) {
       auto args = std::make_shared<SimulateArguments>();
       auto* sub =
           app.add_subcommand("simulate", "Simulate the elastic motion of a mesh under the ARAP energy "
                                          "(implicit Euler), its handles moving to their targets");
       sub->add_option("MESH", args->mesh, "Input mesh (.obj .off .ply .stl)")
           ->required()
           ->check(CLI::ExistingFile);
       auto* constraints = sub->add_option("--constraints", args->constraints,
                                           "Constraints file (as deform; targets reached "
                                           "along straight lines)")
                               ->check(CLI::ExistingFile);
       auto* scenario =
           sub->add_option("--scenario", args->scenario, "Scenario file (handles follow their rigid motions)")
               ->check(CLI::ExistingFile);
       constraints->excludes(scenario);
       sub->add_option("--dt", args->dt, "Time step h")->required()->check(finite_positive);
       sub->add_option("--steps", args->steps, "Number of time steps")
           ->required()
           ->check(CLI::Range(1, 100000000));
       sub->add_option("--damping", args->damping,
                       "Velocity damping D: the free vertices' velocity is scaled by (1 - D) after each step")
           ->check(damping_fraction)
           ->capture_default_str();
       sub->add_option(
              "--ramp", args->ramp,
              "Steps over which the handles move from rest to their targets, then hold (0 = all steps)")
           ->check(CLI::Range(0, 100000000))
           ->capture_default_str();
       sub->add_option("--every", args->every, "Write every K-th frame (and the last)")
           ->check(CLI::Range(1, 100000000))
           ->capture_default_str();
       sub->add_option("--out-dir", args->out_dir,
                       "Folder of the frames frame_NNNNNN.EXT and simulation.json (created; frames move in "
                       "only when the run succeeds)")
           ->required();
       sub->add_option("--format", args->format, "Frame format: obj, off or ply")
           ->check(CLI::IsMember({"obj", "off", "ply"}))
           ->capture_default_str();
       add_external_force_options(*sub, args->forces);
       add_solver_options(*sub, *args);
       sub->add_flag("--json", args->json, "Print the run's report (simulation.json) on stdout");
       sub->add_flag("--quiet", args->quiet, "No progress lines on stderr");
       sub->callback([args] { run_simulate(*args); });
     }});

} // namespace
} // namespace iarap::cli
