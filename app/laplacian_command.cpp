// `iarap laplacian MESH`: writes one Laplace-Beltrami operator as a Matrix Market file and/or reports the
// properties of the operators (paper Section 6, Table 3) as a table or JSON.
#include "command_registry.h"
#include "common/json_text.h"
#include "iarap/core/errors.h"
#include "iarap/io/read_mesh.h"
#include "iarap/laplacian/laplacian_properties.h"
#include "iarap/laplacian/laplacians.h"

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <unistd.h>

namespace {

namespace fs = std::filesystem;

struct LaplacianArgs {
  std::string mesh, kind, out;
  bool properties = false, json = false;
};

// Matrix Market "coordinate real general", 1-based, 17 significant digits (round-trip exact), written to a
// temporary file beside the target and renamed over it, so no reader ever sees a partial file.
void write_matrix_market(const std::string& path, const Eigen::SparseMatrix<double>& L,
                         const std::string& comment) {
  const fs::path target(path);
  const fs::path temporary =
      target.parent_path() / ("." + target.filename().string() + ".tmp." + std::to_string(::getpid()));
  {
    std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
    if (!out) throw iarap::InputError(path + ": cannot create the temporary file " + temporary.string());
    out << "%%MatrixMarket matrix coordinate real general\n% " << comment << "\n";
    out << L.rows() << " " << L.cols() << " " << L.nonZeros() << "\n";
    char line[96];
    for (int col = 0; col < L.outerSize(); ++col)
      for (Eigen::SparseMatrix<double>::InnerIterator it(L, col); it; ++it) {
        std::snprintf(line, sizeof line, "%lld %lld %.17g\n", static_cast<long long>(it.row()) + 1,
                      static_cast<long long>(it.col()) + 1, it.value());
        out << line;
      }
    out.flush();
    if (!out) {
      std::error_code ignored;
      fs::remove(temporary, ignored);
      throw iarap::InputError(path + ": writing failed (disk full or no permission?)");
    }
  }
  std::error_code error;
  fs::rename(temporary, target, error);
  if (error) {
    std::error_code ignored;
    fs::remove(temporary, ignored);
    throw iarap::InputError(path + ": cannot rename the temporary file into place: " + error.message());
  }
}

nlohmann::json to_json(const iarap::LaplacianProperties& p) {
  auto number_or_null = [](double x) {
    return std::isfinite(x) ? nlohmann::json(x) : nlohmann::json(nullptr);
  };
  return {{"kind", p.kind},
          {"symmetric", p.symmetric},
          {"symmetry_error", p.symmetry_error},
          {"local", {{"weak", p.weakly_local}, {"strong", p.strongly_local}}},
          {"sparsity_within_input_adjacency", p.sparsity_within_input_adjacency},
          {"sparsity_within_intrinsic_adjacency", p.sparsity_within_intrinsic_adjacency},
          {"linear_precision_residual", number_or_null(p.linear_precision_residual)},
          {"positive_weights", p.positive_weights},
          {"negative_offdiag_count", p.negative_offdiag_count},
          {"negative_offdiag_max_abs", p.negative_offdiag_max_abs},
          {"negative_offdiag_sum_abs", p.negative_offdiag_sum_abs},
          {"psd", p.psd},
          {"min_eigenvalue", number_or_null(p.min_eigenvalue)},
          {"min_real_part", number_or_null(p.min_real_part)},
          {"gershgorin_real_part_bound", number_or_null(p.gershgorin_real_part_bound)},
          {"row_sum_max_abs", p.row_sum_max_abs},
          {"diagonal_max_abs", p.diagonal_max_abs}};
}

void print_table(const std::vector<iarap::LaplacianProperties>& rows) {
  auto yes = [](bool b) { return b ? "yes" : "no"; };
  char line[320];
  std::snprintf(line, sizeof line, "%-11s %-4s %-5s %-6s %-10s %-4s %-4s %-11s %-11s %-8s %-10s %-10s\n",
                "kind", "sym", "weak", "strong", "lin", "pos", "psd", "min_eig", "min_re", "wrong#",
                "wrong_max", "wrong_sum");
  std::cout << line;
  for (const auto& p : rows) {
    char lin[32];
    if (std::isnan(p.linear_precision_residual))
      std::snprintf(lin, sizeof lin, "n/a");
    else
      std::snprintf(lin, sizeof lin, "%.2e", p.linear_precision_residual);
    std::snprintf(line, sizeof line,
                  "%-11s %-4s %-5s %-6s %-10s %-4s %-4s %-11.3e %-11.3e %-8d %-10.3e %-10.3e\n",
                  p.kind.c_str(), yes(p.symmetric), yes(p.weakly_local), yes(p.strongly_local), lin,
                  yes(p.positive_weights), yes(p.psd), p.min_eigenvalue, p.min_real_part,
                  p.negative_offdiag_count, p.negative_offdiag_max_abs, p.negative_offdiag_sum_abs);
    std::cout << line;
  }
  std::cout << "lin: max |(L x)_i| over interior vertices / (max |L_ii| * bbox diagonal), n/a when not flat; "
               "wrong: off-diagonal entries > 0 (wrong-signed in the -Delta convention)\n";
}

void run(const LaplacianArgs& args) {
  if (args.out.empty() && !args.properties && !args.json)
    throw CLI::ValidationError("laplacian", "nothing to do: give --out FILE.mtx, --properties or --json");
  if (!args.out.empty() && args.kind.empty())
    throw CLI::ValidationError("--out", "--out needs --kind to choose the operator");
  if (!args.out.empty()) {
    std::error_code error;
    if (fs::weakly_canonical(args.out, error) == fs::weakly_canonical(args.mesh) ||
        (fs::exists(args.out) && fs::equivalent(args.out, args.mesh)))
      throw iarap::InputError(args.out + ": refusing to overwrite the input mesh");
  }
  const iarap::MeshData mesh = iarap::read_mesh(args.mesh);
  for (const auto& note : mesh.notes) std::cerr << "iarap: " << args.mesh << ": " << note << "\n";

  std::vector<iarap::LaplacianKind> kinds;
  if (args.kind.empty())
    kinds = iarap::all_laplacian_kinds();
  else
    kinds.push_back(iarap::parse_laplacian_kind(args.kind));
  bool needs_intrinsic = false;
  for (auto kind : kinds) needs_intrinsic = needs_intrinsic || kind != iarap::LaplacianKind::Cotan;
  // Properties measure intrinsic adjacency for every kind, so the triangulation is always built for them.
  std::unique_ptr<iarap::IntrinsicDelaunay> idt;
  if (needs_intrinsic || args.properties || args.json)
    idt = std::make_unique<iarap::IntrinsicDelaunay>(iarap::intrinsic_delaunay(mesh.V, mesh.F));

  if (!args.out.empty()) {
    const Eigen::SparseMatrix<double> L = iarap::laplacian(mesh.V, mesh.F, kinds.front(), idt.get());
    write_matrix_market(args.out, L,
                        "iarap " + args.kind + " Laplacian of " + args.mesh +
                            " (-Delta: L(i,j) = -w_ij, zero row sums)");
    std::cerr << "iarap: wrote " << args.out << " (" << L.rows() << " x " << L.cols() << ", " << L.nonZeros()
              << " entries)\n";
  }
  if (!args.properties && !args.json) return;
  std::vector<iarap::LaplacianProperties> rows;
  for (auto kind : kinds) rows.push_back(iarap::laplacian_properties(mesh.V, mesh.F, kind, idt.get()));
  if (args.json) {
    nlohmann::json array = nlohmann::json::array();
    for (const auto& p : rows) array.push_back(to_json(p));
    std::cout << iarap::cli::json_text(array);
  } else {
    print_table(rows);
  }
}

const bool laplacian_command_registered = iarap::cli::register_command(
    {"laplacian", [](CLI::App& app) {
       auto args = std::make_shared<LaplacianArgs>();
       auto* sub =
           app.add_subcommand("laplacian", "Build a Laplace-Beltrami operator (cotan, intrinsic, iARAP, "
                                           "L+, first-segment) and report its properties (paper Table 3)");
       sub->add_option("mesh", args->mesh, "input mesh (.obj .off .ply .stl)")
           ->required()
           ->check(CLI::ExistingFile);
       sub->add_option("--kind", args->kind, "operator; without it --properties/--json report every kind")
           ->check(
               CLI::IsMember({"cotan", "intrinsic", "iarap", "iarap-plus", "iarap-sym", "iarap-refined"}));
       sub->add_option("--out", args->out, "write the operator as Matrix Market (coordinate real general)");
       sub->add_flag("--properties", args->properties, "print the property table");
       sub->add_flag("--json", args->json, "print the properties as a JSON array, one object per kind");
       sub->callback([args] { run(*args); });
     }});

} // namespace
