// `iarap intrinsic MESH`: the intrinsic Delaunay triangulation's figures, its traced edges as polylines
// (paper Fig. 14) and, for the performance target of the preprocess, a CHOLMOD factorization to compare.
#include "command_registry.h"
#include "common/json_text.h"
#include "mesh_report_json.h"
#include "write_text_file.h"

#include "iarap/core/errors.h"
#include "iarap/core/stopwatch.h"
#include "iarap/core/threads.h"
#include "iarap/intrinsic/intrinsic_delaunay.h"
#include "iarap/io/read_mesh.h"
#include "iarap/mesh/connected_components.h"
#include "iarap/mesh/cotan.h"
#include "iarap/mesh/subdivide.h"
#include "iarap/solver/sparse_cholesky.h"

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

namespace iarap::cli {
namespace {

struct IntrinsicArgs {
  std::string mesh;
  std::string out_edges;
  bool json = false;
  int threads = 0;
  int subdivide = 0;
  bool compare_factorization = false;
  int rounds = 1;
  bool no_mollify = false;
  bool refine_boundary = false;
  bool keep_traces = false;
};

// A memory line of /proc/self/status ("VmHWM": peak resident, "VmRSS": current), in MiB; 0 where /proc is
// not available.
double status_mib(const char* key) {
  std::FILE* status = std::fopen("/proc/self/status", "r");
  if (!status) return 0.0;
  char line[256];
  const std::string prefix = std::string(key) + ":";
  double kib = 0.0;
  while (std::fgets(line, sizeof line, status))
    if (std::strncmp(line, prefix.c_str(), prefix.size()) == 0 &&
        std::sscanf(line + prefix.size(), "%lf", &kib) == 1)
      break;
  std::fclose(status);
  return kib / 1024.0;
}
double peak_rss_mib() {
  return status_mib("VmHWM");
}
double rss_mib() {
  return status_mib("VmRSS");
}

// Bytes held by the segment arrays and B (issue 4's memory budget counts them).
double segments_mib(const Segments& s) {
  const double bytes =
      static_cast<double>(s.edge.size() + s.face.size() + s.b_index.size() + s.edge_start.size()) *
          sizeof(int) +
      static_cast<double>(s.b_value.size() + s.s_hat.size() + s.length.size() + s.weight.size()) *
          sizeof(double) +
      static_cast<double>(s.B.nonZeros()) * (sizeof(double) + sizeof(int)) +
      static_cast<double>(s.B.outerSize() + 1) * sizeof(int);
  return bytes / (1 << 20);
}

// OBJ with the input vertices first (file order), then one vertex per edge crossing, and one `l` record
// per intrinsic edge over its traced points.
std::string traced_edges_obj(const Eigen::MatrixXd& V, const IntrinsicDelaunay& idt) {
  std::ostringstream out;
  out.precision(17);
  out << "# iarap intrinsic Delaunay edges traced over the input mesh: " << idt.triangulation.E.rows()
      << " edges, " << idt.segments.edge.size() << " segments\n";
  for (Eigen::Index v = 0; v < V.rows(); ++v)
    out << "v " << V(v, 0) << ' ' << V(v, 1) << ' ' << V(v, 2) << '\n';
  const auto& tr = idt.traces;
  std::vector<long> index(tr.a.size());
  long next = V.rows() + 1;
  for (size_t p = 0; p < tr.a.size(); ++p) {
    if (tr.c[p] < 0) {
      index[p] = tr.a[p] + 1;
      continue;
    }
    const Eigen::RowVector3d x = (1 - tr.t[p]) * V.row(tr.a[p]) + tr.t[p] * V.row(tr.c[p]);
    out << "v " << x(0) << ' ' << x(1) << ' ' << x(2) << '\n';
    index[p] = next++;
  }
  for (size_t e = 0; e + 1 < tr.start.size(); ++e) {
    out << 'l';
    for (int p = tr.start[e]; p < tr.start[e + 1]; ++p) out << ' ' << index[static_cast<size_t>(p)];
    out << '\n';
  }
  return out.str();
}

// Factorization time of the cotan Laplacian with one vertex per component pinned (what an ARAP
// precompute pays for its global step), the yardstick of the intrinsic preprocess.
double cotan_factorization_ms(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F) {
  int count = 0;
  const Eigen::VectorXi component = vertex_components(F, static_cast<int>(V.rows()), &count);
  std::vector<char> pinned_component(static_cast<size_t>(count), 0);
  std::vector<int> free_index(static_cast<size_t>(V.rows()), -1);
  int n_free = 0;
  for (Eigen::Index v = 0; v < V.rows(); ++v) {
    char& pinned = pinned_component[static_cast<size_t>(component(v))];
    if (!pinned)
      pinned = 1;
    else
      free_index[static_cast<size_t>(v)] = n_free++;
  }
  const Eigen::SparseMatrix<double> L = cotan_laplacian(V, F);
  std::vector<Eigen::Triplet<double>> triplets;
  for (int k = 0; k < L.outerSize(); ++k)
    for (Eigen::SparseMatrix<double>::InnerIterator it(L, k); it; ++it) {
      const int i = free_index[static_cast<size_t>(it.row())], j = free_index[static_cast<size_t>(it.col())];
      if (i >= 0 && j >= 0) triplets.emplace_back(i, j, it.value());
    }
  Eigen::SparseMatrix<double> L_ff(n_free, n_free);
  L_ff.setFromTriplets(triplets.begin(), triplets.end());
  const auto t0 = Clock::now();
  SparseCholesky cholesky(L_ff);
  return ms_since(t0);
}

void run(const IntrinsicArgs& args) {
  set_thread_count(args.threads);
  MeshData mesh = read_mesh(args.mesh);
  subdivide_midpoint(mesh.V, mesh.F, args.subdivide);
  IntrinsicOptions options;
  options.mollify = !args.no_mollify;
  options.refine_boundary = args.refine_boundary;
  options.keep_traces = args.keep_traces || !args.out_edges.empty();
  const double rss_before_mib = rss_mib();
  const double peak_before_mib = peak_rss_mib();
  // The first round is also the one whose memory is reported: later rounds reuse the heap it grew.
  IntrinsicDelaunay idt;
  double total_ms = 0.0;
  double rss_mib = 0.0;
  for (int round = 0; round < args.rounds; ++round) {
    const auto t0 = Clock::now();
    IntrinsicDelaunay next = intrinsic_delaunay(mesh.V, mesh.F, options);
    const double ms = ms_since(t0);
    if (round == 0) rss_mib = peak_rss_mib();
    if (round == 0 || ms < total_ms) {
      total_ms = ms;
      idt = std::move(next);
    }
  }
  // Extra memory the preprocess needed at its peak (valid when it raised the process's peak, which it does
  // unless reading or subdividing peaked higher; reported as 0 then).
  const double preprocess_peak_mib = rss_mib > peak_before_mib ? rss_mib - rss_before_mib : 0.0;
  const double faces_mib = static_cast<double>(mesh.F.size() * sizeof(int)) / (1 << 20);

  nlohmann::json j = intrinsic_summary_json(idt);
  j["file"] = args.mesh;
  j["vertices"] = mesh.V.rows();
  j["faces"] = mesh.F.rows();
  j["threads"] = thread_count();
  j["time_ms"] = total_ms;
  j["rounds"] = args.rounds;
  j["flip_ms"] = idt.flip_ms;
  j["trace_ms"] = idt.trace_ms;
  j["segment_ms"] = idt.segment_ms;
  j["peak_rss_mib"] = rss_mib; // after reading, (subdividing) and the intrinsic preprocess
  j["input_faces_mib"] =
      static_cast<double>(mesh.F.size() * sizeof(int) + mesh.V.size() * sizeof(double)) / (1 << 20);
  j["connectivity_mib"] = faces_mib; // F, #F x 3 ints
  j["segments_mib"] = segments_mib(idt.segments);
  j["traces_kept"] = options.keep_traces;
  j["preprocess_peak_mib"] = preprocess_peak_mib;
  j["memory_budget_mib"] = 2.0 * (faces_mib + j["segments_mib"].get<double>()); // 2 x (F + segments)
  j["obtuse_boundary_before"] = idt.triangulation.obtuse_boundary_before;
  j["obtuse_boundary_after"] = idt.triangulation.obtuse_boundary_after;
  j["inserted_points"] = idt.triangulation.inserted_t.size();
  if (args.compare_factorization) {
    double factor_ms = cotan_factorization_ms(mesh.V, mesh.F);
    for (int round = 1; round < args.rounds; ++round)
      factor_ms = std::min(factor_ms, cotan_factorization_ms(mesh.V, mesh.F));
    j["cotan_factorization_ms"] = factor_ms;
    j["intrinsic_over_factorization"] = total_ms / factor_ms;
  }
  if (!args.out_edges.empty()) {
    if (std::filesystem::exists(args.out_edges) && std::filesystem::equivalent(args.out_edges, args.mesh))
      throw InputError("--out-edges " + args.out_edges + " is the input mesh; refusing to overwrite it");
    write_text_file(args.out_edges, traced_edges_obj(mesh.V, idt));
    j["out_edges"] = args.out_edges;
  }
  if (args.json) {
    std::cout << json_text(j);
    return;
  }
  std::printf("%s: %ld vertices, %ld faces, %d threads\n", args.mesh.c_str(),
              static_cast<long>(mesh.V.rows()), static_cast<long>(mesh.F.rows()), thread_count());
  std::printf("flips %ld, non-Delaunay edges %d -> %d, mollify delta %.3g\n", idt.triangulation.flips,
              idt.triangulation.non_delaunay_before, idt.triangulation.non_delaunay_after,
              idt.triangulation.mollify_delta);
  std::printf("boundary edges with an obtuse opposite angle: %d -> %d (%ld points inserted)\n",
              idt.triangulation.obtuse_boundary_before, idt.triangulation.obtuse_boundary_after,
              static_cast<long>(idt.triangulation.inserted_t.size()));
  std::printf("segments %ld over %ld edges (%.4f per edge, max %d)\n",
              static_cast<long>(idt.segments.edge.size()), static_cast<long>(idt.triangulation.E.rows()),
              j["segments_per_edge"].get<double>(), j["max_segments_per_edge"].get<int>());
  std::printf(
      "time %.1f ms (flip %.1f, trace %.1f, segments %.1f); peak memory %.1f MiB (input V+F %.1f MiB)\n",
      total_ms, idt.flip_ms, idt.trace_ms, idt.segment_ms, rss_mib, j["input_faces_mib"].get<double>());
  std::printf(
      "memory%s: the preprocess peaked %.1f MiB above its start; connectivity F %.1f MiB, segments %.1f MiB, "
      "2 x (F + segments) = %.1f MiB\n",
      options.keep_traces ? " (traces kept)" : "", preprocess_peak_mib, faces_mib,
      j["segments_mib"].get<double>(), j["memory_budget_mib"].get<double>());
  if (args.compare_factorization)
    std::printf(
        "cotan Laplacian CHOLMOD factorization %.1f ms; intrinsic preprocess / factorization = %.3f\n",
        j["cotan_factorization_ms"].get<double>(), j["intrinsic_over_factorization"].get<double>());
  if (!args.out_edges.empty()) std::printf("traced edges written to %s\n", args.out_edges.c_str());
}

const bool intrinsic_command_registered = register_command(
    {"intrinsic", [](CLI::App& app) {
       auto args = std::make_shared<IntrinsicArgs>();
       auto* sub =
           app.add_subcommand("intrinsic", "Intrinsic Delaunay triangulation: figures, traced edges, timing");
       sub->add_option("mesh", args->mesh, "Input mesh (OBJ, OFF, PLY, STL)")
           ->required()
           ->check(CLI::ExistingFile);
       sub->add_option(
           "--out-edges", args->out_edges,
           "Write the traced intrinsic edges as OBJ polylines (input vertices first, in file order)");
       sub->add_flag("--json", args->json, "Print one JSON object");
       sub->add_option("--threads", args->threads, "Threads (0: all)")->check(CLI::NonNegativeNumber);
       sub->add_option("--subdivide", args->subdivide, "Apply K 1-to-4 midpoint subdivisions first")
           ->check(CLI::Range(0, 4));
       sub->add_flag("--compare-factorization", args->compare_factorization,
                     "Also time a CHOLMOD factorization of the mesh's cotan Laplacian");
       sub->add_option("--rounds", args->rounds,
                       "Run the preprocess (and the factorization) R times and report the fastest of each; "
                       "the first round is a cold start that also pays for the process's first page faults")
           ->check(CLI::Range(1, 1000));
       sub->add_flag("--no-mollify", args->no_mollify, "Fail on degenerate triangles instead of mollifying");
       sub->add_flag("--refine-boundary", args->refine_boundary,
                     "Split boundary edges with an obtuse opposite angle (boundary-robust iARAP)");
       sub->add_flag(
           "--keep-traces", args->keep_traces,
           "Keep every edge's traced polyline, as --out-edges does (the memory figures then count them)");
       sub->callback([args] { run(*args); });
     }});

} // namespace
} // namespace iarap::cli
