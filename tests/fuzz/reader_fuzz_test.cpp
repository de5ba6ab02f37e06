// Deterministic mutation fuzzing of every reader: OBJ, OFF, PLY, STL, constraints files and scenarios.
//
// Each test mutates the seed files of tests/fuzz/corpus/<reader>/ (bit flips, byte edits, deleted,
// duplicated and spliced spans, hostile numbers such as 1e400, -1, 2^32, nan, a byte-order mark) with a
// fixed-seed generator and feeds every result to the reader, then a mesh to check_mesh and repair_mesh and
// a scenario to resolve_scenario. The contract under test: an iarap::Error with a message, or a result;
// never another exception, a crash, a hang or a sanitizer report. libFuzzer would need clang's runtime;
// this driver runs inside the normal suite and, with IARAP_SANITIZE, under ASan/UBSan.
//
// Budget per reader: IARAP_FUZZ_SECONDS when set; else 1 s (Release suite) or 6 s under the sanitizers
// (CI's bounded campaign: 6 readers x 6 s, run two at a time). The sequence of inputs is fixed by the seed;
// the budget only decides how far along it a run gets. A failing input is saved under the test's temp
// folder and its path printed, to be added to the corpus once fixed.
#include "iarap/core/errors.h"
#include "iarap/io/read_mesh.h"
#include "iarap/mesh/repair.h"
#include "iarap/mesh/validate.h"
#include "iarap/scene/read_constraints.h"
#include "iarap/scene/read_scenario.h"
#include "iarap/scene/scenario.h"
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

constexpr int kMaxInputs = 200000;        // an upper bound on inputs whatever the budget
constexpr std::size_t kMaxSize = 1 << 16; // mutated inputs stay small: the readers' speed is not under test

double budget_seconds() {
  if (const char* env = std::getenv("IARAP_FUZZ_SECONDS")) return std::max(0.0, std::atof(env));
  return kDefaultSeconds;
}

std::string read_bytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

std::vector<std::string> corpus(const std::string& reader) {
  std::vector<fs::path> files;
  for (const auto& entry : fs::directory_iterator(fs::path(IARAP_SOURCE_DIR) / "tests/fuzz/corpus" / reader))
    files.push_back(entry.path());
  std::sort(files.begin(), files.end()); // directory order is not fixed; the sequence must be
  std::vector<std::string> seeds;
  for (const auto& f : files) seeds.push_back(read_bytes(f));
  return seeds;
}

// Tokens that have broken readers elsewhere: overflow, negative and huge indices, non-numbers, a BOM,
// outlier and extreme coordinates (issue 33: the coincident-vertex check).
const std::vector<std::string> kHostile = {"1e400",
                                           "-1e400",
                                           "nan",
                                           "inf",
                                           "-1",
                                           "0",
                                           "-0",
                                           "4294967296",
                                           "2147483648",
                                           "-2147483649",
                                           "99999999999999999999",
                                           "1e-400",
                                           "1e30",
                                           "-1e30",
                                           "1e300",
                                           "1e-300",
                                           "0x10",
                                           "+",
                                           "-",
                                           ".",
                                           "e5",
                                           "\xef\xbb\xbf",
                                           "\r",
                                           "\t",
                                           "#",
                                           "/",
                                           "//",
                                           "3",
                                           "255",
                                           "65535",
                                           "1.5",
                                           "\"",
                                           "{",
                                           "}",
                                           "[",
                                           "]",
                                           ",",
                                           ":",
                                           "null",
                                           "true",
                                           "\"x\"",
                                           "solid",
                                           "endsolid",
                                           "facet",
                                           "end_header",
                                           "element face 2147483647",
                                           "property list uchar int vertex_indices",
                                           "format binary_little_endian 1.0",
                                           "f",
                                           "v",
                                           "OFF"};

class Mutator {
public:
  Mutator(std::uint32_t seed, std::vector<std::string> seeds) : random_(seed), seeds_(std::move(seeds)) {}

  std::string next() {
    std::string data = seeds_[pick(seeds_.size())];
    const int edits = 1 + static_cast<int>(pick(4));
    for (int k = 0; k < edits; ++k) mutate(data);
    if (data.size() > kMaxSize) data.resize(kMaxSize);
    return data;
  }

private:
  std::size_t pick(std::size_t n) {
    return n == 0 ? 0 : std::uniform_int_distribution<std::size_t>(0, n - 1)(random_);
  }

  void mutate(std::string& data) {
    const std::size_t n = data.size();
    switch (pick(9)) {
    case 0: // flip a bit
      if (n > 0) data[pick(n)] = static_cast<char>(data[pick(n)] ^ (1 << pick(8)));
      break;
    case 1: // overwrite a byte with a digit, a separator or an extreme byte
      if (n > 0) data[pick(n)] = "0123456789-+.e \n#/\x00\xff"[pick(20)];
      break;
    case 2: { // delete a span
      if (n == 0) break;
      const std::size_t at = pick(n);
      data.erase(at, 1 + pick(std::min<std::size_t>(n - at, 32)));
      break;
    }
    case 3: { // duplicate a span
      if (n == 0) break;
      const std::size_t at = pick(n), length = 1 + pick(std::min<std::size_t>(n - at, 64));
      data.insert(pick(n + 1), data.substr(at, length));
      break;
    }
    case 4: // insert a hostile token
      data.insert(pick(n + 1), kHostile[pick(kHostile.size())]);
      break;
    case 5: { // replace a number with a hostile token
      if (n == 0) break;
      std::size_t at = pick(n);
      while (at < n && !std::isdigit(static_cast<unsigned char>(data[at]))) ++at;
      std::size_t end = at;
      while (end < n &&
             (std::isalnum(static_cast<unsigned char>(data[end])) || data[end] == '.' || data[end] == '-'))
        ++end;
      data.replace(at, end - at, kHostile[pick(kHostile.size())]);
      break;
    }
    case 6: // truncate
      data.resize(pick(n + 1));
      break;
    case 7: { // splice: the head of this input, the tail of another seed
      const std::string& other = seeds_[pick(seeds_.size())];
      data = data.substr(0, pick(n + 1)) + other.substr(pick(other.size() + 1));
      break;
    }
    default: // a run of one byte (long tokens, long lines)
      data.insert(pick(n + 1), std::string(1 + pick(300), "9 \n-"[pick(4)]));
      break;
    }
  }

  std::mt19937 random_;
  std::vector<std::string> seeds_;
};

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
