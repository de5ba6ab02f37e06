// `iarap bench MESH...`: precomputation and per-iteration timings of the three ARAP variants.
#include "bench_converge.h"
#include "command_registry.h"
#include "common/json_text.h"
#include "cpu_name.h"
#include "solve_report_json.h"
#include "write_text_file.h"

#include "iarap/core/blas_library.h"
#include "iarap/core/errors.h"
#include "iarap/core/resident_memory.h"
#include "iarap/core/stopwatch.h"
#include "iarap/core/threads.h"
#include "iarap/io/check_output_path.h"
#include "iarap/io/read_mesh.h"
#include "iarap/mesh/subdivide.h"
#include "iarap/mesh/validate.h"
#include "iarap/scene/scenario.h"
#include "iarap/solver/arap.h"

#include "solver/streamed_fit_rotations.h" // the element pass the iterations stream

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <iostream>

namespace iarap::cli {
namespace {

struct BenchArguments {
  std::vector<std::string> meshes;
  std::vector<std::string> methods = {"arap", "spokes-rims", "iarap"};
  int iterations = 10;
  int rounds = 1;
  int threads = 0;
  int subdivide = 0;
  std::string ordering = "auto";
  bool json = false;
  std::string report;
  double converge = 0; // > 0: the convergence bench (bench_converge.h) with this gap
  std::vector<std::string> accelerators = ConvergeSettings{}.accelerators;
  int window = 0;
  int max_iterations = ConvergeSettings{}.max_iterations;
  int drag_steps = 0;
  std::vector<std::string> reference_accelerators = ConvergeSettings{}.reference_accelerators;
};

// The fixed benchmark scene (documented in README.md): the bottom 10% of the bounding box along y is
// fixed, the top 10% along y moves by 10% of the bounding-box diagonal along +x.
Scenario bench_scenario() {
  return band_scenario("bench scenario", Eigen::Vector3d(0.1, 0, 0), 0);
}

// Median of values[first..]: the entries after the warm-up.
double median_after(std::vector<double> values, std::size_t first) {
  if (values.size() <= first) return 0;
  values.erase(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(first));
  const auto middle = values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2);
  std::nth_element(values.begin(), middle, values.end());
  if (values.size() % 2 == 1) return *middle;
  return 0.5 * (*middle + *std::max_element(values.begin(), middle));
}

// The floor an iteration is measured against (issue 18), timed on the precomputed data: the median of
// `repeats` runs of
//  - one CHOLMOD solve of the three right-hand sides with the same factor (solve_floor_ms: cholmod_solve2,
//    the reference), beside one solve as the iterations run it (solve_ms: the project's own
//    supernodal solve over the same factor, src/solver/supernodal_solve.h), and
//  - one streaming pass over the cell-ordered elements (the streamed layout, src/solver/streamed_layout.h)
//  that reads U and writes
//    each cell's 3x3 covariance, nothing else (element_pass_ms): the memory traffic of the local step without
//    its rotation fits, energies and the right-hand side.
struct IterationFloor {
  double cholmod_solve_ms = 0;
  double solve_ms = 0;
  double element_pass_ms = 0;
};

IterationFloor iteration_floor(ArapData& data, const Eigen::MatrixXd& U, int repeats) {
  const ArapElements& el = data.elements;
  std::vector<double> pass_ms, cholmod_ms, solve_ms;
  { // the pass's arrays go before the solves' are made: the process peak is not the bench's own (issue 44)
    ArapElements::ValueRows U_rows;
    detail::visit_rows(el, U, U_rows); // in the order the iterations keep them
    std::vector<Eigen::Matrix3d> S(static_cast<size_t>(el.num_cells));
    for (int r = 0; r < repeats; ++r) {
      auto start = Clock::now();
      detail::cell_covariances(el, U_rows, S);
      pass_ms.push_back(ms_since(start));
    }
  }
  Eigen::MatrixXd B(data.free.size(), 3), X;
  for (Eigen::Index i = 0; i < data.free.size(); ++i) B.row(i) = U.row(data.free(i));
  data.solver.solve(B, X); // the workspaces as the iterations have them
  data.solver.solve_with_cholmod(B, X);
  trace_resident("iteration floor");
  for (int r = 0; r < repeats; ++r) { // alternated, so that a burst of other load hits both alike
    auto start = Clock::now();
    data.solver.solve_with_cholmod(B, X);
    cholmod_ms.push_back(ms_since(start));
    start = Clock::now();
    data.solver.solve(B, X);
    solve_ms.push_back(ms_since(start));
  }
  return {median_after(cholmod_ms, 0), median_after(solve_ms, 0), median_after(pass_ms, 0)};
}

// last_use: no later run reads mesh, whose V and F then go as soon as the precomputation holds its own
// copies (the figure is the whole process's peak: 48 bytes a vertex less, issue 44).
nlohmann::json bench_one(const std::string& path, MeshData& mesh, bool last_use,
                         const ConstraintSet& constraints, const std::string& name, int iterations,
                         FillOrdering ordering) {
  // "iarap" is the tool's default iARAP, with boundary refinement (issue 8, as `deform --boundary refine`);
  // "iarap-paper" is the paper's exact discretization (`deform --boundary paper`).
  ArapOptions options;
  options.method = parse_arap_method(name == "iarap-paper" ? "iarap" : name);
  options.intrinsic.refine_boundary = name == "iarap";
  // Real-world meshes (e.g. ogre.obj, 44 components) have pieces the fixed scene does not reach; pinning
  // one vertex of each keeps them benchmarkable instead of singular.
  options.pin_unconstrained_components = true;
  options.ordering = ordering;
  trace_resident("mesh loaded");
  const auto start = Clock::now();
  ArapData data = arap_precompute(mesh.V, mesh.F, constraints.fixed, options);
  const double precompute_ms = ms_since(start);
  if (last_use) {
    Eigen::MatrixXd().swap(mesh.V);
    Eigen::MatrixXi().swap(mesh.F);
  }
  // The floor first, at the rest positions (its passes cost what they cost at any positions), its arrays
  // and the solves' workspaces freed before the iterations: the process's peak is then the solve's, not
  // the bench's own A/B of two solves (issue 44: 54 B/vertex at 2.77M).
  const IterationFloor floor = iteration_floor(data, data.V, 11);
  data.solver.release_solve_workspaces();
  Eigen::MatrixXd U = data.V; // the input's V
  ArapSolveOptions solve_options;
  solve_options.max_iterations = iterations + 1;     // the first is the warm-up
  solve_options.tolerance = -1;                      // run them all
  solve_options.accelerator = ArapAccelerator::None; // the plain local/global iteration (issue 18's figure)
  const ArapReport report = arap_solve(data, constraints.targets, U, solve_options);
  trace_resident("solved");
  std::vector<double> iteration_ms(report.local_ms_per_iteration.size());
  for (std::size_t k = 0; k < iteration_ms.size(); ++k)
    iteration_ms[k] = report.local_ms_per_iteration[k] + report.global_ms_per_iteration[k];
  nlohmann::json j;
  j["mesh"] = path;
  j["vertices"] = data.V.rows();
  j["faces"] = data.F.rows();
  j["method"] = name;
  j["ordering_used"] = fill_ordering_name(data.solver.used_ordering());
  j["threads"] = thread_count();
  j["precompute_ms"] = precompute_ms;
  j["intrinsic_ms"] = data.timings.intrinsic_ms;
  j["assembly_ms"] = data.timings.assembly_ms;
  j["factor_ms"] = data.timings.factor_ms;
  j["analyze_ms"] = data.timings.analyze_ms;
  j["analysis_overlapped"] = thread_count() > 1;
  j["iteration_ms"] = median_after(iteration_ms, 1);
  j["local_ms"] = median_after(report.local_ms_per_iteration, 1);
  j["global_ms"] = median_after(report.global_ms_per_iteration, 1);
  j["solve_floor_ms"] = floor.cholmod_solve_ms;
  j["solve_ms"] = floor.solve_ms;
  j["element_pass_ms"] = floor.element_pass_ms;
  j["pinned"] = data.pinned.size();
  j["measured_iterations"] = std::max(report.iterations - 1, 0);
  j["factorization"] = factorization_name(arap_factorization(data));
  j["final_energy"] = report.energies.empty() ? report.initial_energy : report.energies.back();
  j["memory"] = memory_json(data);
  return j;
}

// Median over k of a[k] / b[k] (same length, > 0 entries).
double median_paired_ratio(const nlohmann::json& a, const nlohmann::json& b) {
  std::vector<double> ratio;
  for (std::size_t k = 0; k < a.size(); ++k) ratio.push_back(a[k].get<double>() / b[k].get<double>());
  return median_after(ratio, 0);
}

// What each precomputation holds, by part, and the process's resident set (issue 44).
void print_memory(const nlohmann::json& results) {
  // MiB, as ps and /proc report sizes (the IARAP_MEMORY_TRACE lines print decimal MB).
  const auto mib = [](const nlohmann::json& bytes) { return bytes.get<double>() / 1048576.0; };
  for (const auto& r : results) {
    if (r.contains("error") || !r.contains("memory")) continue;
    const nlohmann::json& m = r["memory"];
    const double n = r["vertices"].get<double>();
    std::printf("%s: %s: memory held %.1f MiB (%.0f B/vertex: factor %.0f, kept matrix %.0f, system %.0f, "
                "elements %.0f, streamed %.0f, rotations %.0f, mesh %.0f); resident %.1f MiB, process peak "
                "%.1f MiB (%.0f B/vertex)\n",
                r["mesh"].get<std::string>().c_str(), r["method"].get<std::string>().c_str(), mib(m["total"]),
                m["bytes_per_vertex"].get<double>(), m["factor"].get<double>() / n,
                m["kept_matrix"].get<double>() / n, m["system_matrix"].get<double>() / n,
                m["elements"].get<double>() / n, m["streamed_layout"].get<double>() / n,
                m["rotations"].get<double>() / n, m["mesh"].get<double>() / n, mib(m["resident_bytes"]),
                mib(m["peak_resident_bytes"]), m["peak_resident_bytes"].get<double>() / n);
  }
}

void print_table(const nlohmann::json& results) {
  std::printf("%-28s %9s %-12s %4s %12s %12s %12s %12s %12s %10s %10s %10s %10s %10s\n", "mesh", "vertices",
              "method", "thr", "precompute", "intrinsic", "assembly", "factor", "iteration", "local",
              "global", "solve_fl", "solve", "elem_pass");
  for (const auto& r : results) {
    std::string name = r["mesh"].get<std::string>();
    if (name.size() > 28) name = "..." + name.substr(name.size() - 25);
    if (r.contains("error")) {
      std::printf("%-28s %9lld %-12s failed: %s\n", name.c_str(), r["vertices"].get<long long>(),
                  r["method"].get<std::string>().c_str(), r["error"].get<std::string>().c_str());
      continue;
    }
    std::printf(
        "%-28s %9lld %-12s %4d %12.3f %12.3f %12.3f %12.3f %12.3f %10.3f %10.3f %10.3f %10.3f %10.3f\n",
        name.c_str(), r["vertices"].get<long long>(), r["method"].get<std::string>().c_str(),
        r["threads"].get<int>(), r["precompute_ms"].get<double>(), r["intrinsic_ms"].get<double>(),
        r["assembly_ms"].get<double>(), r["factor_ms"].get<double>(), r["iteration_ms"].get<double>(),
        r["local_ms"].get<double>(), r["global_ms"].get<double>(), r["solve_floor_ms"].get<double>(),
        r["solve_ms"].get<double>(), r["element_pass_ms"].get<double>());
  }
  std::printf(
      "(milliseconds; iteration, local and global are medians over the measured plain local/global "
      "iterations (no accelerator; `--converge` times the accelerated loops); with more "
      "than one thread the symbolic analysis runs beside the intrinsic flips (iarap) or the element build "
      "(the others), and factor counts only the part of it they did not hide; solve_fl (solve_floor_ms): "
      "one CHOLMOD solve (cholmod_solve2) of the 3 right-hand sides, solve (solve_ms): the same solve "
      "as the iterations run it (iarap's supernodal solve over the same factor), elem_pass "
      "(element_pass_ms): one streaming pass over the cell-ordered elements reading U and writing the "
      "3x3 covariances, medians of 11)\n");
  for (const auto& r : results)
    if (!r.contains("error"))
      std::printf(
          "%s: %s: iteration / (solve_floor + element_pass) = %.2f, iteration / (solve + element_pass) "
          "= %.2f\n",
          r["mesh"].get<std::string>().c_str(), r["method"].get<std::string>().c_str(),
          r["iteration_ms"].get<double>() /
              (r["solve_floor_ms"].get<double>() + r["element_pass_ms"].get<double>()),
          r["iteration_ms"].get<double>() /
              (r["solve_ms"].get<double>() + r["element_pass_ms"].get<double>()));
  print_memory(results);
  // Ratios to original ARAP on the same mesh, from this one run: fastest to fastest, and with several rounds
  // also the median of the per-round ratios (round k of each method ran back to back, so a burst of other
  // load mostly cancels out of its ratio: the steadier figure on a shared machine).
  for (const auto& r : results) {
    if (r.contains("error") || r["method"] == "arap") continue;
    for (const auto& base : results) {
      if (base.contains("error") || base["method"] != "arap" || base["mesh"] != r["mesh"]) continue;
      std::printf("%s: %s / arap: precompute %.2fx, iteration %.2fx, local %.2fx",
                  r["mesh"].get<std::string>().c_str(), r["method"].get<std::string>().c_str(),
                  r["precompute_ms"].get<double>() / base["precompute_ms"].get<double>(),
                  r["iteration_ms"].get<double>() / base["iteration_ms"].get<double>(),
                  r["local_ms"].get<double>() / base["local_ms"].get<double>());
      const std::size_t rounds = r["precompute_ms_rounds"].size();
      if (rounds > 1 && base["precompute_ms_rounds"].size() == rounds)
        std::printf("; median of %zu paired rounds: precompute %.2fx, iteration %.2fx", rounds,
                    median_paired_ratio(r["precompute_ms_rounds"], base["precompute_ms_rounds"]),
                    median_paired_ratio(r["iteration_ms_rounds"], base["iteration_ms_rounds"]));
      std::printf("\n");
    }
  }
}

// The result entry of a mesh and method that could not be benchmarked: the other runs go on.
nlohmann::json error_entry(const std::string& path, Eigen::Index vertices, const std::string& method,
                           const std::exception& e) {
  return {{"mesh", path},
          {"vertices", vertices},
          {"method", method},
          {"threads", thread_count()},
          {"error", e.what()}};
}

// What every result shares: the machine, the settings and the scene.
nlohmann::json bench_header(const BenchArguments& args) {
  nlohmann::json j;
  j["cpu"] = cpu_name();
  j["blas"] = blas_library_name();
  j["ordering"] = args.ordering;
  j["threads"] = thread_count();
  // The malloc settings the figures ran under (the tool's own, app/malloc_settings.cpp, or the user's).
  const char* tunables = std::getenv("GLIBC_TUNABLES");
  j["glibc_tunables"] = tunables != nullptr ? tunables : "";
  j["iterations"] = args.iterations;
  j["rounds"] = args.rounds;
  j["warmup_iterations"] = 1;
  j["subdivide"] = args.subdivide;
  j["scenario"] =
      args.converge > 0
          ? "bottom 10% along y fixed; top 10% along y turned 60 degrees about z and "
            "moved by (0.3, -0.1, 0) bbox diagonals"
          : "bottom 10% along y fixed; top 10% along y moved by 10% of the bbox diagonal along +x";
  if (args.converge > 0) j["converge"] = args.converge;
  j["results"] = nlohmann::json::array();
  return j;
}

// Reads the mesh at `path` into mesh, subdivided as asked; throws when it cannot be read or is not usable
// for ARAP (mesh then holds what was read: the error entries give its vertex count).
void load_bench_mesh(const std::string& path, int subdivide, MeshData& mesh) {
  mesh = read_mesh(path);
  subdivide_midpoint(mesh.V, mesh.F, subdivide);
  const MeshReport check = check_mesh(mesh.V, mesh.F);
  if (!check.usable())
    throw TopologyError(path + ": mesh not usable for ARAP: " + check.errors.front() + " (see `iarap info`)");
}

// The convergence bench of one mesh, a result per method appended to results; returns the failed runs.
int converge_mesh(const BenchArguments& args, const std::string& path, const MeshData& mesh,
                  nlohmann::json& results) {
  ConvergeSettings settings{args.converge, args.accelerators, args.window, args.max_iterations};
  settings.drag_steps = args.drag_steps;
  settings.reference_accelerators = args.reference_accelerators;
  int failed = 0;
  for (const std::string& method : args.methods) {
    if (!args.json)
      std::cerr << "bench --converge: " << path << " (" << mesh.V.rows() << " vertices), " << method << "\n";
    try {
      results.push_back(converge_one(path, mesh.V, mesh.F, method, settings));
    } catch (const Error& e) { // as in time_mesh: report it, run the others
      results.push_back(error_entry(path, mesh.V.rows(), method, e));
      ++failed;
    }
  }
  return failed;
}

// Adds round r of a method to its best result so far: every round's precompute and iteration times, and
// the timings of the fastest round of each.
void keep_fastest(nlohmann::json& best, const nlohmann::json& r) {
  if (best.is_null()) {
    best = r;
    best["precompute_ms_rounds"] = nlohmann::json::array({r["precompute_ms"]});
    best["iteration_ms_rounds"] = nlohmann::json::array({r["iteration_ms"]});
    return;
  }
  best["precompute_ms_rounds"].push_back(r["precompute_ms"]);
  best["iteration_ms_rounds"].push_back(r["iteration_ms"]);
  if (r["precompute_ms"].get<double>() < best["precompute_ms"].get<double>())
    for (const char* key : {"precompute_ms", "intrinsic_ms", "assembly_ms", "factor_ms", "analyze_ms"})
      best[key] = r[key];
  if (r["iteration_ms"].get<double>() < best["iteration_ms"].get<double>())
    for (const char* key :
         {"iteration_ms", "local_ms", "global_ms", "solve_floor_ms", "solve_ms", "element_pass_ms"})
      best[key] = r[key];
}

// The timing bench of one mesh, a result per method appended to results; returns the failed runs. Rounds go
// round-robin over the methods, so that a burst of other load on a shared machine hits every method alike
// instead of one method's block of rounds; each method keeps its fastest round. The last run releases the
// mesh's arrays (bench_one).
int time_mesh(const BenchArguments& args, const std::string& path, MeshData& mesh,
              const ConstraintSet& constraints, nlohmann::json& results) {
  int failed = 0;
  const Eigen::Index vertices = mesh.V.rows();
  std::vector<nlohmann::json> best(args.methods.size());
  for (int round = 0; round < args.rounds; ++round)
    for (std::size_t m = 0; m < args.methods.size(); ++m) {
      const std::string& method = args.methods[m];
      if (best[m].contains("error")) continue;
      if (!args.json && round == 0) {
        std::cerr << "bench: " << path << " (" << mesh.V.rows() << " vertices), " << method << "\n";
      }
      try {
        const bool last_use = round + 1 == args.rounds && m + 1 == args.methods.size();
        nlohmann::json r = bench_one(path, mesh, last_use, constraints, method, args.iterations,
                                     parse_fill_ordering(args.ordering));
        r["rounds"] = args.rounds;
        keep_fastest(best[m], r);
      } catch (const Error& e) { // e.g. original ARAP on zero-area faces: report it, time the others
        best[m] = error_entry(path, vertices, method, e);
        ++failed;
      }
    }
  for (const auto& r : best) results.push_back(r);
  return failed;
}

void print_results(const BenchArguments& args, const nlohmann::json& j) {
  if (args.converge > 0) {
    std::printf("cpu: %s, threads: %d, blas: %s\n", j["cpu"].get<std::string>().c_str(), thread_count(),
                j["blas"].get<std::string>().c_str());
    print_converge_table(j["results"], args.converge);
  } else {
    std::printf("cpu: %s, threads: %d, blas: %s, ordering: %s, %d measured iterations after 1 warm-up\n",
                j["cpu"].get<std::string>().c_str(), thread_count(), j["blas"].get<std::string>().c_str(),
                j["ordering"].get<std::string>().c_str(), args.iterations);
    print_table(j["results"]);
  }
}

void run_bench(const BenchArguments& args) {
  if (!args.report.empty()) check_output_path(args.report); // before the runs, which can take minutes
  set_thread_count(args.threads);
  nlohmann::json j = bench_header(args);
  int failed = 0;
  for (const auto& path : args.meshes) {
    // A mesh that cannot be benchmarked gets an error entry and the others still run: results are printed
    // and the exit status is 1 at the end.
    MeshData mesh;
    ConstraintSet constraints;
    try {
      load_bench_mesh(path, args.subdivide, mesh);
      constraints = resolve_scenario(bench_scenario(), mesh.V);
    } catch (const Error& e) {
      if (!args.json) std::cerr << "bench: " << path << ": skipped: " << e.what() << "\n";
      for (const auto& method : args.methods)
        j["results"].push_back(error_entry(path, mesh.V.rows(), method, e));
      ++failed;
      continue;
    }
    failed += args.converge > 0 ? converge_mesh(args, path, mesh, j["results"])
                                : time_mesh(args, path, mesh, constraints, j["results"]);
  }
  const std::string text = json_text(j);
  if (!args.report.empty()) write_text_file(args.report, text);
  if (args.json)
    std::cout << text;
  else
    print_results(args, j);
  if (failed > 0)
    throw Error(std::to_string(failed) + " benchmark run(s) failed (see \"error\" in the results)");
}

const bool bench_command_registered = register_command(
    {"bench", [](CLI::App& app) {
       auto args = std::make_shared<BenchArguments>();
       auto* sub = app.add_subcommand(
           "bench",
           "Time precomputation and iterations of the ARAP variants on a fixed scene: the bottom 10% along y "
           "fixed, the top 10% along y moved by 10% of the bounding-box diagonal along +x; one vertex of "
           "each component the scene does not reach is pinned");
       sub->add_option("MESH", args->meshes, "Mesh files")->required()->check(CLI::ExistingFile);
       sub->add_option("--methods", args->methods,
                       "Comma-separated subset of arap,spokes-rims,iarap,iarap-paper (iarap refines obtuse "
                       "boundary edges like `deform --boundary refine`; iarap-paper does not)")
           ->delimiter(',')
           ->check(CLI::IsMember({"arap", "spokes-rims", "iarap", "iarap-paper"}))
           ->capture_default_str();
       sub->add_option("--iterations", args->iterations,
                       "Measured iterations per run (after 1 warm-up), >= 1")
           ->check(CLI::Range(1, 100000))
           ->capture_default_str();
       sub->add_option("--rounds", args->rounds,
                       "Repeat precompute + iterations R times per mesh and method and keep the fastest "
                       "(less disturbed by other load)")
           ->check(CLI::Range(1, 1000))
           ->capture_default_str();
       sub->add_option("--threads", args->threads, "Threads for the parallel loops; 0 = all hardware threads")
           ->check(CLI::Range(0, 4096))
           ->capture_default_str();
       sub->add_option("--subdivide", args->subdivide,
                       "Apply K midpoint 1-to-4 subdivisions first (4^K x faces)")
           ->check(CLI::Range(0, 6))
           ->capture_default_str();
       sub->add_option(
              "--ordering", args->ordering,
              "CHOLMOD's fill-reducing ordering: auto (amd below 1M free vertices, metis from there), amd "
              "(faster analysis) or metis (smaller factor)")
           ->check(CLI::IsMember({"auto", "amd", "metis"}))
           ->capture_default_str();
       sub->add_option(
              "--converge", args->converge,
              "Instead of timing iterations: iterations and ms of each accelerator to reach an energy within "
              "TOL (relative) of a reference minimum, on the scene of data/bend60_scenario.json")
           ->check(CLI::PositiveNumber);
       sub->add_option("--accels", args->accelerators,
                       "With --converge: comma-separated subset of none,anderson,lbfgs,newton,hybrid")
           ->delimiter(',')
           ->check(CLI::IsMember({"none", "anderson", "lbfgs", "newton", "hybrid"}))
           ->capture_default_str();
       sub->add_option("--window", args->window,
                       "With --converge: accelerator history length (0 = the default)")
           ->check(CLI::Range(0, 1000));
       sub->add_option("--max-iterations", args->max_iterations,
                       "With --converge: iteration limit of each run")
           ->check(CLI::Range(1, 10000000))
           ->capture_default_str();
       sub->add_option(
              "--drag-steps", args->drag_steps,
              "With --converge: start every run where a drag ends, the handle brought to its place in "
              "N steps of one plain iteration each (0: from the rest shape)")
           ->check(CLI::Range(0, 100000))
           ->capture_default_str();
       sub->add_option("--reference-accels", args->reference_accelerators,
                       "With --converge: comma-separated accelerators of the reference run (the lowest "
                       "energy wins)")
           ->delimiter(',')
           ->check(CLI::IsMember({"none", "anderson", "lbfgs", "newton", "hybrid"}))
           ->capture_default_str();
       sub->add_flag("--json", args->json, "Print the results as one JSON object instead of a table");
       sub->add_option("--report", args->report, "Also write the JSON results to this file (atomically)");
       sub->callback([args] { run_bench(*args); });
     }});

} // namespace
} // namespace iarap::cli
