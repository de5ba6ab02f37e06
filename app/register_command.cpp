// `iarap register SOURCE TARGET --out OUT`: non-rigid ICP of a mesh onto a mesh or point cloud with the ARAP
// energy as the regularizer (iarap/registration/register.h), written to a mesh file with the source's
// numbering.
#include "command_registry.h"
#include "common/json_text.h"
#include "same_file.h"
#include "solve_option_flags.h"
#include "write_text_file.h"

#include "iarap/core/errors.h"
#include "iarap/core/stopwatch.h"
#include "iarap/core/threads.h"
#include "iarap/io/check_output_path.h"
#include "iarap/io/read_mesh.h"
#include "iarap/io/write_mesh.h"
#include "iarap/mesh/validate.h"
#include "iarap/registration/register.h"
#include "iarap/scene/read_constraints.h"
#include "iarap/solver/arap.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <iostream>
#include <memory>
#include <string>

namespace iarap::cli {
namespace {

struct RegisterArguments {
  std::string source, target, out, landmarks, report, method = "iarap", prealign = "rigid";
  RegistrationOptions options;
  int threads = 0, normal_neighbours = 12;
  bool json = false, quiet = false;
};

void check_arguments(const RegisterArguments& args) {
  for (const std::string* input : {&args.source, &args.target}) {
    if (same_file(args.out, *input))
      throw CLI::ValidationError("--out " + args.out + " is an input file; refusing to overwrite it");
    if (!args.report.empty() && same_file(args.report, *input))
      throw CLI::ValidationError("--report " + args.report + " is an input file");
  }
  if (!args.report.empty() && same_file(args.report, args.out))
    throw CLI::ValidationError("--report " + args.report + " is the output mesh");
  check_mesh_output_path(args.out);
  if (!args.report.empty()) check_output_path(args.report);
}

// a over b (same column count, either may have no row).
template <class M> M stack(const M& a, const M& b) {
  M c(a.rows() + b.rows(), std::max(a.cols(), b.cols()));
  if (a.rows() > 0) c.topRows(a.rows()) = a;
  if (b.rows() > 0) c.bottomRows(b.rows()) = b;
  return c;
}

// An empty matrix as 0 x 3.
Eigen::MatrixXd rows3(const Eigen::MatrixXd& m) {
  return m.rows() == 0 ? Eigen::MatrixXd(0, 3) : m;
}

// Every line of the landmarks file (a constraints file: 'i x y z', 'b f b0 b1 b2 x y z', optionally with a
// weight W) becomes a landmark held softly: with W when given, else with --landmark-weight.
RegistrationLandmarks read_landmarks(const std::string& path, const MeshData& source,
                                     double landmark_weight) {
  const ConstraintSet set =
      read_constraints(path, static_cast<int>(source.V.rows()), static_cast<int>(source.F.rows()));
  const SoftConstraintSet& soft = set.soft;
  RegistrationLandmarks l;
  const Eigen::Index hard = set.fixed.size(), hb = soft.hard_faces.size();
  l.vertices = stack(set.fixed, soft.vertices);
  l.vertex_targets = stack(rows3(set.targets), rows3(soft.vertex_targets));
  l.vertex_weights = stack(Eigen::VectorXd::Constant(hard, landmark_weight).eval(), soft.vertex_weights);
  l.faces = stack(soft.faces, soft.hard_faces);
  l.barycentric = stack(rows3(soft.barycentric), rows3(soft.hard_barycentric));
  l.face_targets = stack(rows3(soft.face_targets), rows3(soft.hard_targets));
  l.face_weights = stack(soft.face_weights, Eigen::VectorXd::Constant(hb, landmark_weight).eval());
  return l;
}

nlohmann::json statistics_json(const DistanceStatistics& s) {
  nlohmann::json j;
  visit_distance_statistics(s, [&j](const char* name, double value) { j[name] = value; });
  return j;
}

nlohmann::json rounds_json(const RegistrationReport& report) {
  nlohmann::json rounds = nlohmann::json::array();
  for (const RegistrationRound& r : report.rounds) {
    nlohmann::json j;
    visit_registration_round(r, report.target_diagonal,
                             [&j](const char* name, auto value) { j[name] = value; });
    rounds.push_back(std::move(j));
  }
  return rounds;
}

void run_register(RegisterArguments args) {
  check_arguments(args);
  const auto total_start = Clock::now();
  const MeshData source = read_mesh(args.source);
  const MeshReport check = check_mesh(source.V, source.F);
  if (!check.usable()) {
    std::string message = args.source + ": mesh not usable for ARAP:";
    for (const auto& error : check.errors) message += "\n  " + error;
    throw TopologyError(message + "\n(`iarap repair` fixes most of these)");
  }
  const RegistrationLandmarks landmarks =
      args.landmarks.empty() ? RegistrationLandmarks{}
                             : read_landmarks(args.landmarks, source, args.options.landmark_weight);
  const RegistrationTarget target = read_registration_target(args.target, args.normal_neighbours);
  set_thread_count(args.threads == 0 ? automatic_thread_count(static_cast<int>(source.V.rows()))
                                     : args.threads);

  RegistrationOptions& options = args.options;
  options.method = parse_arap_method(args.method);
  options.prealignment = parse_prealignment(args.prealign);
  if (!args.quiet) {
    std::cerr << "register: " << args.source << " (" << source.V.rows() << " vertices) onto " << args.target
              << " (" << target.points.rows() << " points, " << target.faces.rows() << " faces), "
              << landmarks.size() << " landmarks\n";
    options.on_round = [&](const RegistrationRound& r) {
      std::cerr << "register: stage " << r.stage + 1 << "/" << options.stages << " round " << r.round + 1
                << " weight " << r.data_weight << " mean distance " << r.mean_distance / target.diagonal
                << " median " << r.median_distance / target.diagonal << " (of the diagonal), kept "
                << r.forward_used << " + " << r.backward_used << ", " << r.solver_iterations
                << " iterations (closest " << r.closest_ms << " ms, factor " << r.factor_ms << " ms, solve "
                << r.solve_ms << " ms)\n";
    };
  }
  const RegistrationResult result = register_to_target(source.V, source.F, target, landmarks, options);
  const RegistrationReport& report = result.report;
  write_mesh(args.out, result.U, source.F);

  nlohmann::json j;
  j["source"] = args.source;
  j["target"] = args.target;
  j["landmarks"] = landmarks.size();
  j["method"] = arap_method_name(options.method);
  j["vertices"] = source.V.rows();
  j["faces"] = source.F.rows();
  j["target_points"] = target.points.rows();
  j["target_faces"] = target.faces.rows();
  j["target_normals"] = target.oriented ? "given or from the mesh" : "estimated (PCA)";
  j["target_diagonal"] = report.target_diagonal;
  j["prealignment"] = {
      {"kind", args.prealign},
      {"rounds", report.prealign_rounds},
      {"scale", report.prealignment.s},
      {"rotation", std::vector<double>(report.prealignment.R.data(), report.prealignment.R.data() + 9)},
      {"translation", {report.prealignment.t(0), report.prealignment.t(1), report.prealignment.t(2)}}};
  j["rounds"] = rounds_json(report);
  j["initial_distance"] = statistics_json(report.initial_distance);
  j["final_distance"] = statistics_json(report.final_distance); // fractions of the target's diagonal
  j["prealign_ms"] = report.prealign_ms;
  j["precompute_ms"] = report.precompute_ms;
  j["closest_ms"] = report.closest_ms;
  j["factor_ms"] = report.factor_ms;
  j["solve_ms"] = report.solve_ms;
  j["register_ms"] = report.total_ms;
  j["threads"] = thread_count();
  j["output"] = args.out;
  j["total_ms"] = ms_since(total_start);
  const std::string text = json_text(j);
  if (!args.report.empty()) write_text_file(args.report, text);
  if (args.json) std::cout << text;
  if (!args.quiet) {
    const DistanceStatistics& d = report.final_distance;
    std::cerr << "register: final distance to the target (of its diagonal): mean " << d.mean << ", median "
              << d.median << ", 90% " << d.p90 << ", max " << d.max << "\nregister: wrote " << args.out
              << "\n";
  }
}

const bool register_command_registered = register_command(
    {"register", [](CLI::App& app) {
       auto args = std::make_shared<RegisterArguments>();
       auto* sub = app.add_subcommand(
           "register", "Fit a mesh onto a target mesh or point cloud: non-rigid ICP with the ARAP energy as "
                       "the regularizer, stiff to soft");
       sub->add_option("SOURCE", args->source, "Source mesh to deform (.obj .off .ply .stl)")
           ->required()
           ->check(CLI::ExistingFile);
       sub->add_option(
              "TARGET", args->target,
              "Target: a mesh, or a point cloud (vertex-only .ply or .obj, or .xyz 'x y z [nx ny nz]')")
           ->required()
           ->check(CLI::ExistingFile);
       sub->add_option("--out", args->out,
                       "Output mesh (.obj .off .ply): the source deformed, same numbering")
           ->required();
       sub->add_option("--landmarks", args->landmarks,
                       "Landmarks: a constraints file ('i x y z', 'b f b0 b1 b2 x y z', an optional weight W "
                       "last), held softly")
           ->check(CLI::ExistingFile);
       sub->add_option("--method", args->method, "ARAP energy of the regularizer: arap, spokes-rims or iarap")
           ->check(CLI::IsMember({"arap", "spokes-rims", "iarap"}))
           ->capture_default_str();
       sub->add_option("--prealign", args->prealign, "Pre-alignment: none, rigid or similarity (with scale)")
           ->check(CLI::IsMember({"none", "rigid", "similarity"}))
           ->capture_default_str();
       RegistrationOptions& o = args->options;
       sub->add_option("--stages", o.stages, "Stages from stiff to soft")
           ->check(CLI::Range(1, 100))
           ->capture_default_str();
       sub->add_option("--rounds", o.rounds_per_stage, "ICP rounds per stage at most")
           ->check(CLI::Range(1, 10000))
           ->capture_default_str();
       sub->add_option("--initial-weight", o.initial_data_weight, "Data weight of the first (stiffest) stage")
           ->check(CLI::PositiveNumber)
           ->capture_default_str();
       sub->add_option("--final-weight", o.final_data_weight, "Data weight of the last (softest) stage")
           ->check(CLI::PositiveNumber)
           ->capture_default_str();
       sub->add_option("--landmark-weight", o.landmark_weight, "Weight of a landmark without its own")
           ->check(CLI::PositiveNumber)
           ->capture_default_str();
       sub->add_option("--point-to-plane", o.point_to_plane, "0: point-to-point, 1: point-to-plane targets")
           ->check(CLI::Range(0.0, 1.0))
           ->capture_default_str();
       sub->add_option("--backward-weight", o.backward_weight,
                       "Weight of the target -> source correspondences")
           ->check(CLI::NonNegativeNumber)
           ->capture_default_str();
       sub->add_option("--reject-distance", o.reject_distance,
                       "Reject correspondences beyond this x the median")
           ->check(CLI::PositiveNumber)
           ->capture_default_str();
       sub->add_option("--reject-angle", o.reject_angle_degrees,
                       "Reject correspondences whose normals differ more")
           ->check(CLI::Range(1.0, 180.0))
           ->capture_default_str();
       sub->add_option("--normal-neighbours", args->normal_neighbours,
                       "Neighbours of a point cloud's PCA normals")
           ->check(CLI::Range(3, 1000))
           ->capture_default_str();
       add_solve_option_flags(*sub, o.solve);
       sub->add_option("--threads", args->threads, "Threads for the parallel loops; 0 = all hardware threads")
           ->check(CLI::Range(0, 4096))
           ->capture_default_str();
       sub->add_flag("--json", args->json, "Print the run's report as one JSON object on stdout");
       sub->add_option("--report", args->report, "Also write the JSON report to this file (atomically)");
       sub->add_flag("--quiet", args->quiet, "No progress lines on stderr");
       sub->callback([args] { run_register(*args); });
     }});

} // namespace
} // namespace iarap::cli
