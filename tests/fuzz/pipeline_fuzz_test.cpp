// Issue 33: the fuzz campaign of the whole `deform --repair` path. Mutations (mutator.h) of small valid and
// dirty OBJ, OFF and PLY files (tests/fuzz/corpus/{obj,off,ply,dirty}) go through read_mesh, repair_mesh
// with deform's options, check_mesh and, where the repaired mesh is usable, arap_precompute and one solve
// with each of the three methods (repair_pipeline.h). Every input must end in success or an iarap::Error;
// a repaired mesh must also be manifold and consistently oriented (unless a piece is non-orientable).
//
// Inputs: IARAP_FUZZ_PIPELINE_INPUTS when set (the campaign: 10000), else 2000 (the suite, ~20 s). The
// sequence is fixed by the seed, so a run of N inputs is the first N of any longer run. Prints the outcomes
// by category, the wall time and the slowest input; a failing input is saved under the test's temp folder
// (kept, with the slowest input, when the test fails).
#include "iarap/core/errors.h"
#include "iarap/core/threads.h"
#include "mesh/repair_pipeline.h"
#include "mutator.h"
#include "test_support.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cstdlib>
#include <iostream>
#include <map>
#include <string>
#include <utility>
#include <vector>

namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

int input_count() {
  if (const char* env = std::getenv("IARAP_FUZZ_PIPELINE_INPUTS")) return std::max(1, std::atoi(env));
  return 2000;
}

// The kind of an error message, for the outcome table: the first of these words it contains.
std::string error_kind(const std::string& message) {
  const std::pair<const char*, const char*> kinds[] = {
      {"non-orientable", "non-orientable"},
      {"NaN or Inf", "NaN or Inf coordinate"},
      {"no faces", "no faces"},
      {"repeats a vertex", "face repeating a vertex"},
      {"non-manifold", "non-manifold"},
      {"inconsistently oriented", "inconsistent orientation"},
      {"singular", "singular system"},
      {"degenerate", "degenerate face"},
      {"tracing", "intrinsic tracing failed"},
      {"no constrained vertex", "unconstrained component"},
      {"ends", "truncated"},
      {"bytes follow", "truncated"},
      {"face", "bad face record"},
      {"corner", "bad face record"},
      {"vertex", "bad vertex record"},
      {"coordinate", "bad vertex record"},
      {"header", "bad header"},
      {"element", "bad header"},
      {"format", "bad header"},
      {"ply", "bad header"},
      {"property", "bad header"},
      {"OFF", "bad header"}};
  for (const auto& [word, kind] : kinds)
    if (message.find(word) != std::string::npos) return kind;
  return "other";
}

// Runs one file through the pipeline; returns its outcome category.
std::string run_pipeline(const std::string& path) {
  iarap::MeshData mesh;
  try {
    mesh = iarap::read_mesh(path);
  } catch (const iarap::Error& e) {
    return std::string("read refused: ") + error_kind(e.what());
  }
  iarap::RepairResult repaired;
  try {
    repaired = iarap::repair_mesh(mesh.V, mesh.F, iarap::test::deform_repair_options());
  } catch (const iarap::Error& e) {
    return std::string("repair refused: ") + error_kind(e.what());
  }
  const iarap::MeshReport check = iarap::check_mesh(repaired.V, repaired.F);
  if (check.non_finite_coordinates == 0) iarap::test::expect_repaired_topology(repaired, path);
  if (!check.usable()) return "check refused after repair: " + error_kind(check.errors.front());
  // Each method on its own: one refusing (degenerate geometry) says nothing about the others.
  std::string refused;
  for (const iarap::ArapMethod method : iarap::test::every_method) {
    try {
      iarap::test::deform_with(method, repaired.V, repaired.F, 1);
    } catch (const iarap::Error& e) {
      if (std::getenv("IARAP_FUZZ_PRINT_SOLVER")) std::cout << "solver: " << e.what() << "\n";
      refused +=
          (refused.empty() ? "" : ", ") + iarap::arap_method_name(method) + " (" + error_kind(e.what()) + ")";
    }
  }
  const std::string how = repaired.actions.empty() ? "deformed as it was" : "repaired and deformed";
  return refused.empty() ? how + " (3 methods)" : how + "; solver refused: " + refused;
}

} // namespace

TEST(Fuzz, RepairAndDeformPipeline) {
  iarap::set_thread_count(1); // meshes of a few faces: a thread team costs more than it saves, under load 50x
  std::vector<std::string> seeds, extensions;
  for (const char* folder : {"obj", "off", "ply", "dirty"})
    for (const fs::path& file : iarap::test::fuzz::corpus_files(folder)) {
      seeds.push_back(iarap::test::fuzz::read_bytes(file));
      extensions.push_back(file.extension().string());
    }
  iarap::test::fuzz::Mutator mutator(33, seeds, 2); // fewer edits: more inputs get past the reader
  const fs::path dir = iarap::test::temp_dir("fuzz_pipeline");
  const int count = input_count();
  std::map<std::string, int> outcomes;
  double slowest_ms = 0;
  int slowest = -1;
  const auto start = Clock::now();
  for (int i = 0; i < count; ++i) {
    const std::string data = mutator.next();
    const std::string path = (dir / ("input" + extensions[mutator.last_seed()])).string();
    std::ofstream(path, std::ios::binary | std::ios::trunc) << data;
    const auto input_start = Clock::now();
    const int failures_before =
        ::testing::UnitTest::GetInstance()->current_test_info()->result()->total_part_count();
    try {
      ++outcomes[run_pipeline(path)];
    } catch (const std::exception& e) {
      ADD_FAILURE() << "input " << i << " threw a non-iarap exception: " << e.what();
    }
    const double ms = std::chrono::duration<double, std::milli>(Clock::now() - input_start).count();
    if (ms > slowest_ms) {
      slowest_ms = ms;
      slowest = i;
      std::ofstream(dir / ("slowest" + extensions[mutator.last_seed()]), std::ios::binary | std::ios::trunc)
          << data;
    }
    if (::testing::UnitTest::GetInstance()->current_test_info()->result()->total_part_count() >
        failures_before) {
      const fs::path saved = dir / ("failure_" + std::to_string(i) + extensions[mutator.last_seed()]);
      std::ofstream(saved, std::ios::binary) << data;
      ADD_FAILURE() << "input " << i << " saved as " << saved.string();
      break;
    }
  }
  const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
  std::cout << "pipeline fuzz: " << count << " inputs in " << seconds << " s; slowest: input " << slowest
            << ", " << slowest_ms << " ms\n";
  int total = 0;
  for (const auto& [outcome, n] : outcomes) {
    std::cout << "  " << n << "  " << outcome << "\n";
    total += n;
  }
  EXPECT_EQ(total, count);
  if (!::testing::Test::HasFailure()) fs::remove_all(dir);
  iarap::set_thread_count(0);
}
