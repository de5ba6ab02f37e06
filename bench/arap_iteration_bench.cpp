// Per-iteration cost of the three ARAP variants: local step (element vectors, covariances, rotations,
// energy) and global step (right-hand side gather and the 3-column solve), for 1 and 2 threads.
// Meshes: data/bunny.off and, when present, beetle.off from $IARAP_SHARED_MESHES or ../shared/meshes.
// Scenario: bottom 10% along y fixed, top 10% moved up by 10% of the bounding box diagonal.
#include "iarap/core/threads.h"
#include "iarap/io/read_mesh.h"
#include "iarap/solver/arap.h"
#include "shared_meshes.h"

#include <benchmark/benchmark.h>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

namespace {

struct Problem {
  iarap::MeshData mesh;
  Eigen::VectorXi fixed;
  Eigen::MatrixXd targets;
};

Problem make_problem(const std::string& path) {
  Problem p{iarap::read_mesh(path), {}, {}};
  const Eigen::MatrixXd& V = p.mesh.V;
  const double lo = V.col(1).minCoeff(), hi = V.col(1).maxCoeff();
  const double diag = (V.colwise().maxCoeff() - V.colwise().minCoeff()).norm();
  std::vector<int> fixed;
  std::vector<bool> top;
  for (int v = 0; v < V.rows(); ++v) {
    const double t = (V(v, 1) - lo) / (hi - lo);
    if (t <= 0.1 || t >= 0.9) {
      fixed.push_back(v);
      top.push_back(t >= 0.9);
    }
  }
  p.fixed = Eigen::Map<Eigen::VectorXi>(fixed.data(), static_cast<Eigen::Index>(fixed.size()));
  p.targets.resize(p.fixed.size(), 3);
  for (Eigen::Index k = 0; k < p.fixed.size(); ++k) {
    p.targets.row(k) = V.row(p.fixed(k));
    if (top[static_cast<size_t>(k)]) p.targets(k, 1) += 0.1 * diag;
  }
  return p;
}

void BM_ArapIteration(benchmark::State& state, const std::string& path, iarap::ArapMethod method) {
  const Problem p = make_problem(path);
  iarap::set_thread_count(static_cast<int>(state.range(0)));
  iarap::ArapOptions options;
  options.method = method;
  options.keep_elements = true; // the element count below
  iarap::ArapData data = iarap::arap_precompute(p.mesh.V, p.mesh.F, p.fixed, options);
  iarap::ArapSolveOptions solve;
  solve.max_iterations = 10;
  solve.tolerance = -1.0; // a fixed number of iterations
  double local = 0, global = 0;
  long iterations = 0;
  for (auto _ : state) {
    Eigen::MatrixXd U = p.mesh.V;
    const iarap::ArapReport report = iarap::arap_solve(data, p.targets, U, solve);
    for (int k = 0; k < report.iterations; ++k) {
      local += report.local_ms_per_iteration[static_cast<size_t>(k)];
      global += report.global_ms_per_iteration[static_cast<size_t>(k)];
    }
    iterations += report.iterations;
  }
  state.counters["vertices"] = static_cast<double>(p.mesh.V.rows());
  state.counters["elements"] = static_cast<double>(data.elements.size());
  state.counters["local_ms"] = local / static_cast<double>(iterations);
  state.counters["global_ms"] = global / static_cast<double>(iterations);
  state.counters["step_ms"] = (local + global) / static_cast<double>(iterations);
  state.counters["factor_ms"] = data.timings.factor_ms;
  state.counters["intrinsic_ms"] = data.timings.intrinsic_ms;
  state.SetLabel(iarap::factorization_name(iarap::arap_factorization(data)));
  iarap::set_thread_count(0);
}

} // namespace

int main(int argc, char** argv) {
  std::vector<std::pair<std::string, std::string>> meshes = {
      {"bunny", std::string(IARAP_SOURCE_DIR) + "/data/bunny.off"}};
  if (const std::string beetle = iarap::bench::shared_mesh("beetle.off"); !beetle.empty())
    meshes.emplace_back("beetle", beetle);
  for (const auto& [name, path] : meshes)
    for (iarap::ArapMethod method :
         {iarap::ArapMethod::Arap, iarap::ArapMethod::SpokesRims, iarap::ArapMethod::Iarap})
      benchmark::RegisterBenchmark(("ArapIteration/" + name + "/" + iarap::arap_method_name(method)).c_str(),
                                   BM_ArapIteration, path, method)
          ->ArgName("threads")
          ->Arg(1)
          ->Arg(2)
          ->Unit(benchmark::kMillisecond)
          ->UseRealTime();
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
