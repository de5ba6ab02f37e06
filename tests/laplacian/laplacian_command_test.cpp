// Tests of `iarap laplacian`: the Matrix Market file, the JSON report, refusals.
#include "iarap/io/read_mesh.h"
#include "iarap/laplacian/laplacians.h"
#include "test_support.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <sys/wait.h>

namespace iarap {
namespace {

#ifdef IARAP_CLI_PATH

struct CommandResult {
  int exit_code;
  std::string output;
};

CommandResult run_cli(const std::string& arguments) {
  const std::string command = std::string(IARAP_CLI_PATH) + " " + arguments + " 2>/dev/null";
  FILE* pipe = ::popen(command.c_str(), "r");
  if (!pipe) return {-1, ""};
  std::string output;
  char buffer[4096];
  while (size_t n = std::fread(buffer, 1, sizeof buffer, pipe)) output.append(buffer, n);
  const int status = ::pclose(pipe);
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, output};
}

// The written file is Matrix Market coordinate real general, 1-based, with the library's exact values.
TEST(LaplacianCommand, WritesMatrixMarket) {
  const auto dir = test::temp_dir("laplacian_mtx");
  const std::string bunny = test::data_path("bunny.off"), out = (dir / "L.mtx").string();
  const CommandResult result = run_cli("laplacian " + bunny + " --kind iarap-plus --out " + out);
  ASSERT_EQ(result.exit_code, 0);
  const MeshData mesh = read_mesh(bunny);
  const Eigen::SparseMatrix<double> L = laplacian(mesh.V, mesh.F, LaplacianKind::IarapPlus);
  std::ifstream in(out);
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line, "%%MatrixMarket matrix coordinate real general");
  while (std::getline(in, line) && line[0] == '%') {
  }
  std::istringstream header(line);
  long rows = 0, cols = 0, entries = 0;
  header >> rows >> cols >> entries;
  EXPECT_EQ(rows, mesh.V.rows());
  EXPECT_EQ(cols, mesh.V.rows());
  ASSERT_EQ(entries, L.nonZeros());
  Eigen::SparseMatrix<double> read(rows, cols);
  std::vector<Eigen::Triplet<double>> triplets;
  long i = 0, j = 0;
  double value = 0;
  while (in >> i >> j >> value) triplets.emplace_back(i - 1, j - 1, value);
  ASSERT_EQ(static_cast<long>(triplets.size()), entries);
  read.setFromTriplets(triplets.begin(), triplets.end());
  EXPECT_EQ(Eigen::MatrixXd(read - L).cwiseAbs().maxCoeff(), 0.0); // %.17g round-trips doubles
  std::filesystem::remove_all(dir);
}

TEST(LaplacianCommand, JsonReportsEveryKind) {
  const CommandResult result = run_cli("laplacian " + test::data_path("bunny.off") + " --json");
  ASSERT_EQ(result.exit_code, 0);
  const nlohmann::json report = nlohmann::json::parse(result.output);
  ASSERT_EQ(report.size(), all_laplacian_kinds().size());
  for (const auto& row : report) {
    for (const char* key : {"symmetric", "local", "linear_precision_residual", "positive_weights", "psd",
                            "min_eigenvalue", "negative_offdiag_count", "negative_offdiag_max_abs"})
      EXPECT_TRUE(row.contains(key)) << key;
    EXPECT_TRUE(row["linear_precision_residual"].is_null()); // the bunny is not flat
  }
  EXPECT_EQ(report[2]["kind"], "iarap");
  EXPECT_EQ(report[2]["symmetric"], true);
  // Strongly local, measured: it is the cotan Laplacian (docs/operator-identity.md).
  EXPECT_EQ(report[2]["local"]["strong"], true);
  EXPECT_EQ(report[1]["kind"], "intrinsic");
  EXPECT_EQ(report[1]["local"]["strong"], false);
  EXPECT_EQ(report[3]["kind"], "iarap-plus");
  EXPECT_EQ(report[3]["positive_weights"], true);
}

TEST(LaplacianCommand, RefusesToOverwriteTheInput) {
  const auto dir = test::temp_dir("laplacian_self");
  const auto copy = dir / "bunny.off";
  std::filesystem::copy_file(test::data_path("bunny.off"), copy);
  const auto size = std::filesystem::file_size(copy);
  EXPECT_EQ(run_cli("laplacian " + copy.string() + " --kind cotan --out " + copy.string()).exit_code, 1);
  EXPECT_EQ(std::filesystem::file_size(copy), size);
  std::filesystem::remove_all(dir);
}

TEST(LaplacianCommand, UsageErrors) {
  const std::string bunny = test::data_path("bunny.off");
  EXPECT_EQ(run_cli("laplacian " + bunny + " --kind laplace --out /tmp/x.mtx").exit_code, 2);
  EXPECT_EQ(run_cli("laplacian " + bunny).exit_code, 2);                       // nothing to do
  EXPECT_EQ(run_cli("laplacian " + bunny + " --out /tmp/x.mtx").exit_code, 2); // --out without --kind
}

#endif

} // namespace
} // namespace iarap
