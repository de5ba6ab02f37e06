// Deterministic mutation fuzzing of every reader: OBJ, OFF, PLY, STL, constraints, forces, stiffness and
// rigid-group files, scenarios, and the tetrahedral meshes (MEDIT .mesh, gmsh .msh).
//
// Each test mutates the seed files of tests/fuzz/corpus/<reader>/ (bit flips, byte edits, deleted,
// duplicated and spliced spans, hostile numbers such as 1e400, -1, 2^32, nan, a byte-order mark) with a
// fixed-seed generator and feeds every result to the reader, then a mesh to check_mesh and repair_mesh and
// a scenario to resolve_scenario. The contract under test: an iarap::Error with a message, or a result;
// never another exception, a crash, a hang or a sanitizer report. libFuzzer would need clang's runtime;
// this driver runs inside the normal suite and, with IARAP_SANITIZE, under ASan/UBSan.
//
// Budget per reader: IARAP_FUZZ_SECONDS when set; else 1 s (Release suite) or 6 s under the sanitizers
// (CI's bounded campaign: 10 readers x 6 s, run two at a time; scripts/fuzz.sh runs the long one). The
// sequence of inputs is fixed by the seed; the budget only decides how far along it a run gets. A failing
// input is saved under the test's temp folder and its path printed, to be added to the corpus once fixed.
#include "iarap/core/errors.h"
#include "iarap/io/read_mesh.h"
#include "iarap/io/read_tet_mesh.h"
#include "iarap/mesh/repair.h"
#include "iarap/mesh/validate.h"
#include "iarap/scene/read_constraints.h"
#include "iarap/scene/read_forces.h"
#include "iarap/scene/read_rigid_groups.h"
#include "iarap/scene/read_scenario.h"
#include "iarap/scene/read_stiffness.h"
#include "iarap/scene/scenario.h"
#include "mutator.h"
#include "test_support.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <random>
#include <sstream>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;
using iarap::test::fuzz::corpus;
using iarap::test::fuzz::Mutator;

#if defined(__SANITIZE_ADDRESS__)
constexpr double kDefaultSeconds = 6;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
constexpr double kDefaultSeconds = 6;
#else
constexpr double kDefaultSeconds = 1;
#endif
#else
constexpr double kDefaultSeconds = 1;
#endif

constexpr int kMaxInputs = 200000; // an upper bound on inputs whatever the budget

double budget_seconds() {
  if (const char* env = std::getenv("IARAP_FUZZ_SECONDS")) return std::max(0.0, std::atof(env));
  return kDefaultSeconds;
}

// The 4-vertex mesh the constraints and scenarios refer to.
Eigen::MatrixXd tetrahedron() {
  Eigen::MatrixXd V(4, 3);
  V << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1;
  return V;
}

// Runs `consume` on mutated inputs written to a file with `extension` until the budget is spent. Returns
// how many inputs ran; records a test failure (with the saved input) for anything but iarap::Error.
int fuzz(const std::string& reader, const std::string& extension, std::uint32_t seed,
         const std::function<void(const std::string&)>& consume) {
  const fs::path dir = iarap::test::temp_dir("fuzz_" + reader);
  const std::string path = (dir / ("input" + extension)).string();
  Mutator mutator(seed, corpus(reader));
  const auto start = std::chrono::steady_clock::now();
  const double budget = budget_seconds();
  int inputs = 0, rejected = 0;
  for (; inputs < kMaxInputs; ++inputs) {
    if (std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() >= budget &&
        inputs > 0)
      break;
    const std::string data = mutator.next();
    std::ofstream(path, std::ios::binary | std::ios::trunc) << data;
    try {
      consume(path);
    } catch (const iarap::Error& e) {
      ++rejected;
      EXPECT_GT(std::string(e.what()).size(), 0u);
    } catch (const std::exception& e) {
      const std::string saved = (dir / ("failure_" + std::to_string(inputs) + extension)).string();
      std::ofstream(saved, std::ios::binary) << data;
      ADD_FAILURE() << reader << " input " << inputs << " (seed " << seed << ", saved as " << saved
                    << ") threw a non-iarap exception: " << e.what();
      break;
    }
  }
  std::cout << reader << ": " << inputs << " mutated inputs, " << rejected << " rejected with an error\n";
  return inputs;
}

void read_check_repair(const std::string& path) {
  const iarap::MeshData mesh = iarap::read_mesh(path);
  const iarap::MeshReport report = iarap::check_mesh(mesh.V, mesh.F); // never throws
  EXPECT_EQ(report.vertices, mesh.V.rows());
  if (report.out_of_range_indices == 0) {
    iarap::RepairOptions options;
    options.remove_zero_area = true;
    iarap::repair_mesh(mesh.V, mesh.F, options);
  }
}

} // namespace

TEST(Fuzz, ObjReader) {
  EXPECT_GT(fuzz("obj", ".obj", 1, read_check_repair), 0);
}
TEST(Fuzz, OffReader) {
  EXPECT_GT(fuzz("off", ".off", 2, read_check_repair), 0);
}
TEST(Fuzz, PlyReader) {
  EXPECT_GT(fuzz("ply", ".ply", 3, read_check_repair), 0);
}
TEST(Fuzz, StlReader) {
  EXPECT_GT(fuzz("stl", ".stl", 4, read_check_repair), 0);
}

TEST(Fuzz, ConstraintsReader) {
  EXPECT_GT(fuzz("constraints", ".txt", 5, [](const std::string& path) { iarap::read_constraints(path, 4); }),
            0);
}

TEST(Fuzz, ScenarioReader) {
  const Eigen::MatrixXd V = tetrahedron();
  EXPECT_GT(fuzz("scenario", ".json", 6,
                 [&](const std::string& path) { iarap::resolve_scenario(iarap::read_scenario(path), V); }),
            0);
}

TEST(Fuzz, ForcesReader) {
  EXPECT_GT(fuzz("forces", ".txt", 7, [](const std::string& path) { iarap::read_forces(path, 4); }), 0);
}

TEST(Fuzz, StiffnessReader) {
  EXPECT_GT(fuzz("stiffness", ".txt", 8, [](const std::string& path) { iarap::read_stiffness(path, 4); }), 0);
}

TEST(Fuzz, RigidGroupsReader) {
  EXPECT_GT(fuzz("rigid", ".txt", 11, [](const std::string& path) { iarap::read_rigid_groups(path, 6); }), 0);
}

TEST(Fuzz, MeditTetReader) {
  EXPECT_GT(fuzz("medit", ".mesh", 9, [](const std::string& path) { iarap::read_tet_mesh(path); }), 0);
}

TEST(Fuzz, GmshTetReader) {
  EXPECT_GT(fuzz("gmsh", ".msh", 10, [](const std::string& path) { iarap::read_tet_mesh(path); }), 0);
}
