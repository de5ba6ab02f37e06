// The whole ARAP parameterization (checks, initial map, factorization, iterations; no file I/O) of the
// shared disks of issue 31 (camelhead, lion, face), each phase as a counter, for the three energies with
// the defaults (flip-free, LSCM start) and the plain per-triangle iteration. One thread, as `iarap param`.
#include "iarap/core/threads.h"
#include "iarap/io/read_mesh.h"
#include "iarap/param/arap_parameterize.h"
#include "shared_meshes.h"

#include <benchmark/benchmark.h>
#include <string>
#include <vector>

namespace {

void BM_ArapParameterize(benchmark::State& state, const std::string& path, iarap::ParamOptions options) {
  const iarap::MeshData mesh = iarap::read_mesh(path);
  iarap::set_thread_count(1);
  iarap::ParamReport report;
  for (auto _ : state) report = iarap::arap_parameterize(mesh.V, mesh.F, options).report;
  state.counters["vertices"] = static_cast<double>(mesh.V.rows());
  state.counters["iterations"] = report.iterations;
  state.counters["flipped"] = report.distortion.flipped;
  state.counters["scaled_energy"] = report.distortion.scaled_energy;
  state.counters["check_ms"] = report.check_ms;
  state.counters["init_ms"] = report.init_ms;
  state.counters["cells_ms"] = report.cells_ms;
  state.counters["factor_ms"] = report.factor_ms;
  state.counters["iterate_ms"] = report.iterate_ms;
  iarap::set_thread_count(0);
}

} // namespace

int main(int argc, char** argv) {
  struct Variant {
    std::string name;
    iarap::ParamOptions options;
  };
  std::vector<Variant> variants(4);
  variants[0].name = "triangle";
  variants[1].name = "triangle-allow-flips";
  variants[1].options.allow_flips = true;
  variants[2].name = "iarap";
  variants[2].options.energy = iarap::ParamEnergy::Iarap;
  variants[3].name = "arap";
  variants[3].options.energy = iarap::ParamEnergy::Arap;
  for (const char* name : {"camelhead.off", "lion.off", "face.obj"}) {
    const std::string path = iarap::bench::shared_mesh(name);
    if (path.empty()) continue;
    for (const Variant& variant : variants)
      benchmark::RegisterBenchmark(("ArapParameterize/" + std::string(name) + "/" + variant.name).c_str(),
                                   BM_ArapParameterize, path, variant.options)
          ->Unit(benchmark::kMillisecond)
          ->UseRealTime();
  }
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
