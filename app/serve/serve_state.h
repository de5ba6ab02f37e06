// The deformation session behind `iarap serve`: one mesh, its fixed and handle vertices, and one ARAP
// solver state per method (arap, spokes-rims, iarap), shared by all HTTP requests under one mutex.
//
// Constrained vertices are fixed ++ handle, in that order. When they are set, each method records its
// current positions of them as anchors: fixed vertices stay at their anchors, handle vertices go to the
// anchors moved by the request's affine transform (or to explicit targets). Each method keeps its own
// deformed positions U, the warm start of its next solve, and its factorization, refactorized only when
// the constrained set changes (libigl habit: new targets reuse it).
#pragma once
#include "iarap/intrinsic/intrinsic_delaunay.h"
#include "iarap/io/read_mesh.h"
#include "iarap/solver/arap.h"

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

namespace iarap::serve {

inline constexpr std::array<ArapMethod, 3> all_methods = {ArapMethod::Arap, ArapMethod::SpokesRims,
                                                          ArapMethod::Iarap};

struct MeshSummary {
  std::string name;
  int vertices = 0, faces = 0;
  double bbox_diagonal = 0;
  std::vector<std::string> notes, warnings; // reader notes and check_mesh warnings
};

struct SolveRequest {
  ArapMethod method = ArapMethod::Iarap;
  int iterations = 5;
  double tolerance = 1e-6; // ArapSolveOptions::tolerance; negative: exactly `iterations`
  // Handle targets: anchors moved by transform (4 x 4 affine, last row 0 0 0 1), or given as #handle x 3.
  std::optional<Eigen::Matrix4d> transform;
  std::optional<Eigen::MatrixXd> handle_targets;
  bool cell_energy = false; // also return arap_cell_energy of the result
};

struct SolveResult {
  ArapReport report;
  double precompute_ms = 0; // > 0 when this solve built or refactorized the method's data
  double solve_ms = 0;
  int pinned = 0;                 // vertices pinned because their component had no constrained vertex
  std::vector<float> positions;   // #V x 3 row-major
  std::vector<float> cell_energy; // #V when requested
};

// Intrinsic Delaunay edges traced over the input (TracedEdges, CSR): point p of edge e, for p in
// start[e] .. start[e+1]-1, is (1 - t[p]) U[a[p]] + t[p] U[c[p]] (c = -1: the vertex a[p]).
struct IntrinsicOverlay {
  std::vector<std::int32_t> start, a, c;
  std::vector<float> t;
  std::vector<std::int32_t> original; // #E 1 when the intrinsic edge is still an input edge
};

struct MeshSnapshot {
  Eigen::MatrixXd V;
  Eigen::MatrixXi F;
  std::string name;
};

class ServeState {
public:
  // Replaces the mesh (and clears constraints and solver states) after check_mesh. Throws TopologyError
  // listing check_mesh's errors; the previous mesh then stays.
  void load_mesh(const std::string& name, MeshData mesh);

  bool has_mesh() const;
  // The calls below throw HttpError 409 when no mesh is loaded.
  MeshSummary mesh_summary() const;
  Eigen::VectorXi fixed() const;
  Eigen::VectorXi handle() const;

  // Throws InputError naming the position for an index out of range, a repeat within a set, or a vertex
  // in both sets; nothing changes then. Empty sets are allowed (solve then answers 409).
  void set_constraints(const Eigen::VectorXi& fixed, const Eigen::VectorXi& handle);

  // Precomputes the method on first use, refactorizes after a constraint change, then runs arap_solve from
  // the method's current U. Throws HttpError 409 without constrained vertices, InputError for a target
  // shape or value at fault, TopologyError / SolverError from the solver; the state is unchanged then.
  SolveResult solve(const SolveRequest& request);

  // Every method back to the rest positions; anchors re-taken there; constraints and factorizations kept.
  void reset();

  // #V x 3 row-major current positions of a method, or the rest positions without one.
  std::vector<float> positions(std::optional<ArapMethod> method) const;
  // #F x 3 row-major face indices.
  std::vector<std::uint32_t> faces() const;
  // The method's current positions with the faces, for writing a file.
  MeshSnapshot snapshot(ArapMethod method) const;
  // Built on first call for the rest mesh (intrinsic_delaunay), then cached until the next load.
  std::shared_ptr<const IntrinsicOverlay> intrinsic_overlay();

private:
  struct MethodState {
    std::optional<ArapData> data; // built lazily; its fixed set may lag behind constrained_ until a solve
    Eigen::MatrixXd U;            // #V x 3 current positions
    Eigen::MatrixXd anchor;       // #constrained x 3 positions of the constrained vertices when set
  };

  void require_mesh() const;
  MethodState& state_of(ArapMethod method);
  const MethodState& state_of(ArapMethod method) const;
  Eigen::MatrixXd targets_for(const MethodState& state, const SolveRequest& request) const;

  mutable std::mutex mutex_;
  std::optional<MeshData> mesh_;
  MeshSummary summary_;
  Eigen::VectorXi fixed_, handle_, constrained_;
  std::array<MethodState, 3> methods_;
  std::shared_ptr<const IntrinsicOverlay> overlay_;
};

} // namespace iarap::serve
