// The ARAP class: arap_precompute once per mesh and constrained set, arap_solve for every new set of
// targets. Heavy work runs without the GIL; a mutex keeps two Python threads off one solver at a time.
#include "bindings.h"
#include "numpy_arrays.h"
#include "solve_option_keywords.h"

#include "iarap/core/errors.h"
#include "iarap/core/stopwatch.h"
#include "iarap/io/tet_mesh.h"
#include "iarap/solver/arap.h"
#include "iarap/solver/arap_tets.h"

#include <memory>
#include <mutex>
#include <optional>

namespace iarap::python {
namespace {

// One ARAP problem: the precomputed data, the last solve's report and how often L_ff was factorized.
class ArapSolver {
public:
  ArapSolver(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, const Eigen::VectorXi& fixed,
             const ArapSoftConstraints& soft, const ArapOptions& options)
      : data_(F.cols() == 4 ? arap_precompute_tets(V, F, fixed, soft, options)
                            : arap_precompute(V, F, fixed, soft, options)) {}

  // Everything below locks mutex_; callers release the GIL first so that a waiting thread never holds it.
  Eigen::MatrixXd solve(const Eigen::MatrixXd& targets, const Eigen::MatrixXd& soft_targets,
                        Eigen::MatrixXd U, const ArapSolveOptions& options) {
    std::lock_guard<std::mutex> lock(mutex_);
    const auto start = Clock::now();
    ArapReport report = arap_solve(data_, targets, soft_targets, U, options);
    solve_ms_ = ms_since(start);
    report_ = std::move(report);
    return U;
  }

  void set_fixed(const Eigen::VectorXi& fixed) {
    std::lock_guard<std::mutex> lock(mutex_);
    arap_set_fixed(data_, fixed);
    ++factorizations_;
  }

  void set_soft_weights(const Eigen::VectorXd& vertex_weights, const Eigen::VectorXd& face_weights) {
    std::lock_guard<std::mutex> lock(mutex_);
    arap_set_soft_weights(data_, vertex_weights, face_weights);
    ++factorizations_;
  }

  template <typename Function> auto with_data(Function&& f) const {
    std::lock_guard<std::mutex> lock(mutex_);
    return f(data_);
  }

  std::optional<ArapReport> report() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return report_;
  }
  double solve_ms() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return solve_ms_;
  }
  int factorizations() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return factorizations_;
  }

private:
  mutable std::mutex mutex_;
  ArapData data_;
  std::optional<ArapReport> report_;
  double solve_ms_ = 0;
  int factorizations_ = 1; // arap_precompute factorizes once
};

// Runs f(data) under the solver's lock with the GIL released and returns its (C++) result.
template <typename Function> auto without_gil(const ArapSolver& solver, Function&& f) {
  py::gil_scoped_release release;
  return solver.with_data(std::forward<Function>(f));
}

Eigen::Index vertex_count(const ArapSolver& solver) {
  return without_gil(solver, [](const ArapData& d) { return d.V.rows(); });
}

// Made from a #V x 2 V: positions in and out have 2 columns.
bool is_planar(const ArapSolver& solver) {
  return without_gil(solver, [](const ArapData& d) { return d.planar; });
}

// A 1-D array-like of weights (None: empty) as a vector; their values are checked by the library.
Eigen::VectorXd to_weights(const py::object& weights, const std::string& name) {
  if (weights.is_none()) return {};
  const auto a = py::array_t<double, py::array::forcecast>::ensure(weights);
  if (!a || a.ndim() != 1) throw InputError(name + " must be a 1-D array of weights");
  Eigen::VectorXd w(a.shape(0));
  for (py::ssize_t k = 0; k < a.shape(0); ++k) w(k) = a.at(k);
  return w;
}

// The soft constraints of the ARAP constructor (each argument None or an array; see its docstring).
ArapSoftConstraints to_soft(const py::object& vertices, const py::object& weights, const py::object& faces,
                            const py::object& barycentric, const py::object& face_weights,
                            const py::object& hard_faces, const py::object& hard_barycentric, Eigen::Index n,
                            Eigen::Index face_count) {
  ArapSoftConstraints soft;
  if (!vertices.is_none()) soft.vertices = to_indices(vertices, "soft_vertices", n);
  soft.vertex_weights = to_weights(weights, "soft_weights");
  if (!faces.is_none()) soft.faces = to_indices(faces, "soft_faces", face_count);
  if (!barycentric.is_none()) soft.barycentric = to_points(barycentric, "soft_barycentric");
  soft.face_weights = to_weights(face_weights, "soft_face_weights");
  if (!hard_faces.is_none()) soft.hard_faces = to_indices(hard_faces, "hard_faces", face_count);
  if (!hard_barycentric.is_none()) soft.hard_barycentric = to_points(hard_barycentric, "hard_barycentric");
  return soft;
}

// F given as (#T, 4): tetrahedra.
bool has_four_columns(const py::object& F) {
  const py::array a = py::array::ensure(F);
  return a && a.ndim() == 2 && a.shape(1) == 4;
}

// rigid_groups=: a sequence of sequences of vertex indices (None: no group).
std::vector<std::vector<int>> to_groups(const py::object& groups) {
  std::vector<std::vector<int>> out;
  if (groups.is_none()) return out;
  for (const py::handle group : groups) {
    std::vector<int> members;
    try {
      for (const py::handle v : group) members.push_back(v.cast<int>());
    } catch (const std::exception&) {
      throw InputError("rigid_groups[" + std::to_string(out.size()) +
                       "] must be a sequence of integer vertex indices");
    }
    out.push_back(std::move(members));
  }
  return out;
}

std::unique_ptr<ArapSolver>
make_solver(const py::object& V, const py::object& F, const py::object& fixed, const std::string& method,
            bool pin_unconstrained_components, bool refine_boundary, const py::object& soft_vertices,
            const py::object& soft_weights, const py::object& soft_faces, const py::object& soft_barycentric,
            const py::object& soft_face_weights, const py::object& hard_faces,
            const py::object& hard_barycentric, const py::object& stiffness, const py::object& rigid_groups) {
  // #V x 2: a planar mesh, deformed in its plane (rotations about z); solves then take and give 2 columns.
  const Eigen::MatrixXd positions = to_points(V, "V", true, -1, "", true);
  // (#T, 4): tetrahedra (arap_precompute_tets); soft points then lie on their boundary faces.
  const bool tets = has_four_columns(F);
  const Eigen::MatrixXi faces = to_faces(F, "F", positions.rows(), tets ? 4 : 3);
  const Eigen::VectorXi constrained = to_indices(fixed, "fixed", positions.rows());
  const ArapSoftConstraints soft =
      to_soft(soft_vertices, soft_weights, soft_faces, soft_barycentric, soft_face_weights, hard_faces,
              hard_barycentric, positions.rows(), tets ? tet_boundary_faces(faces).rows() : faces.rows());
  ArapOptions options;
  options.method = parse_arap_method(method);
  options.pin_unconstrained_components = pin_unconstrained_components;
  options.intrinsic.refine_boundary = refine_boundary;
  options.stiffness = to_weights(stiffness, "stiffness"); // checked by the library, naming the vertex
  options.rigid_groups = to_groups(rigid_groups);         // checked by the library, naming the group
  py::gil_scoped_release release;
  return std::make_unique<ArapSolver>(positions, faces, constrained, soft, options);
}

// ARAP.solve's parameters: targets, U0, the solve options (iterations and tolerance positional, as they
// always were), then soft_targets and forces.
KeywordSignature solve_signature() {
  std::vector<Parameter> parameters = {{"targets", "npt.ArrayLike", py::object(), false},
                                       {"U0", "npt.ArrayLike | None", py::none(), false}};
  for (Parameter& p : solve_option_parameters(ArapSolveOptions{}, 2)) parameters.push_back(std::move(p));
  parameters.push_back({"soft_targets", "npt.ArrayLike | None", py::none(), true});
  parameters.push_back({"forces", "npt.ArrayLike | None", py::none(), true});
  return KeywordSignature("solve", std::move(parameters), "numpy.ndarray");
}

py::array_t<double> solve_py(ArapSolver& solver, const BoundArguments& arguments) {
  const py::object &targets = arguments["targets"], &U0 = arguments["U0"];
  const py::object &soft_targets = arguments["soft_targets"], &forces = arguments["forces"];
  const auto [n, fixed_count] =
      without_gil(solver, [](const ArapData& d) { return std::make_pair(d.V.rows(), d.fixed.size()); });
  const Eigen::Index soft_count = without_gil(solver, [](const ArapData& d) { return d.soft.size(); });
  const bool planar = is_planar(solver);
  const Eigen::MatrixXd target_rows = to_points(targets, "targets", true, fixed_count, "#fixed", planar);
  if (soft_count > 0 && soft_targets.is_none())
    throw InputError("soft_targets: the solver has " + std::to_string(soft_count) +
                     " soft constraints; give their targets, (#soft, 3)");
  const Eigen::MatrixXd soft_rows =
      soft_targets.is_none() ? Eigen::MatrixXd(0, planar ? 2 : 3)
                             : to_points(soft_targets, "soft_targets", true, soft_count, "#soft", planar);
  Eigen::MatrixXd U = U0.is_none() ? without_gil(solver,
                                                 [planar](const ArapData& d) {
                                                   return planar ? Eigen::MatrixXd(d.V.leftCols(2)) : d.V;
                                                 })
                                   : to_points(U0, "U0", true, n, "#V", planar);
  ArapSolveOptions options;
  set_solve_options(options, arguments);
  if (!forces.is_none()) options.forces = to_points(forces, "forces", true, n, "#V", planar);
  {
    py::gil_scoped_release release;
    U = solver.solve(target_rows, soft_rows, std::move(U), options);
  }
  return to_numpy(U);
}

py::object report_py(const ArapSolver& solver) {
  std::optional<ArapReport> report;
  double solve_ms = 0;
  ArapPrecomputeTimings timings;
  {
    py::gil_scoped_release release;
    report = solver.report();
    solve_ms = solver.solve_ms();
    timings = solver.with_data([](const ArapData& d) { return d.timings; });
  }
  if (!report) return py::none();
  py::dict d = arap_report_dict(*report);
  d["solve_ms"] = solve_ms;
  d["intrinsic_ms"] = timings.intrinsic_ms;
  d["assembly_ms"] = timings.assembly_ms;
  d["factor_ms"] = timings.factor_ms;
  d["analyze_ms"] = timings.analyze_ms;
  return std::move(d);
}

py::array_t<double> rotations_py(const ArapSolver& solver) {
  const std::vector<Eigen::Matrix3d> R =
      without_gil(solver, [](const ArapData& d) { return std::vector<Eigen::Matrix3d>(arap_rotations(d)); });
  py::array_t<double> out({static_cast<py::ssize_t>(R.size()), py::ssize_t{3}, py::ssize_t{3}});
  auto o = out.mutable_unchecked<3>();
  for (std::size_t v = 0; v < R.size(); ++v)
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) o(static_cast<py::ssize_t>(v), i, j) = R[v](i, j);
  return out;
}

py::dict intrinsic_py(const ArapSolver& solver) {
  const ArapIntrinsicSummary s = without_gil(solver, [](const ArapData& d) { return d.intrinsic; });
  py::dict d;
  d["flips"] = s.flips;
  d["non_delaunay_before"] = s.non_delaunay_before;
  d["non_delaunay_after"] = s.non_delaunay_after;
  d["mollify_delta"] = s.mollify_delta;
  d["intrinsic_edges"] = s.intrinsic_edges;
  d["segments"] = s.segments;
  d["tufted_cover"] = s.tufted_cover;
  d["cover_vertices"] = s.cover_vertices;
  return d;
}

// Applies f(data, U) to a checked #V x 3 (planar: #V x 2) U without the GIL.
template <typename Function> auto on_positions(const ArapSolver& solver, const py::object& U, Function&& f) {
  const Eigen::MatrixXd positions = to_points(U, "U", true, vertex_count(solver), "#V", is_planar(solver));
  return without_gil(solver, [&](const ArapData& d) { return f(d, positions); });
}

// ARAP.solve, its keywords from the schema of the solve options: signature and docs are assembled here.
void def_solve(py::class_<ArapSolver>& arap) {
  const auto signature = std::make_shared<const KeywordSignature>(solve_signature());
  py::options options; // the docstring's first line is the signature, from the schema
  options.disable_function_signatures();
  arap.def(
      "solve",
      [signature](ArapSolver& s, const py::args& args, const py::kwargs& kwargs) {
        return solve_py(s, signature->bind(args, kwargs));
      },
      (signature->text() + R"(

Deforms the mesh: returns U, float64 (#V, 3), with U[fixed] == targets.

targets: (#fixed, 3) positions of the constrained vertices, in the order of `fixed`.
U0: (#V, 3) initial guess (None: the rest positions); its constrained rows are replaced by the targets.
Warm start: pass the previous solution as U0.
)" + solve_option_docs() +
       R"(report["stop_reason"] says which rule stopped the solve.
soft_targets: (#soft, 3) targets of the soft constraints (vertices first, then soft face points, then hard
face points), required when there are any; new soft targets reuse the factorization.
forces: (#V, 3) external forces f (None: none): minimizes E_ARAP + penalty - f . (U - V), the statics of
constant forces (gravity: vertex_masses(V, F)[:, None] * g); report["potential"] is -f . (U - V).
The run is described by `report`; rotations of U by `rotations`.)")
          .c_str());
}

// The constrained set and the soft constraints: fixed, set_soft_weights, penalty.
void def_constraints(py::class_<ArapSolver>& arap) {
  arap.def_property(
          "fixed",
          [](const ArapSolver& s) {
            return to_numpy(without_gil(s, [](const ArapData& d) { return Eigen::VectorXi(d.fixed); }));
          },
          [](ArapSolver& s, const py::object& fixed) {
            const Eigen::VectorXi constrained = to_indices(fixed, "fixed", vertex_count(s));
            py::gil_scoped_release release;
            s.set_fixed(constrained);
          },
          "(#fixed,) int64 constrained vertices. Assigning a new set refactorizes L_ff (only).")
      .def(
          "set_soft_weights",
          [](ArapSolver& s, const py::object& weights, const py::object& face_weights) {
            const Eigen::VectorXd w = to_weights(weights, "soft_weights"),
                                  wf = to_weights(face_weights, "soft_face_weights");
            py::gil_scoped_release release;
            s.set_soft_weights(w, wf);
          },
          py::arg("soft_weights"), py::arg("soft_face_weights") = py::none(),
          "New weights for the soft vertices and face points: a numeric refactorization only (the symbolic "
          "analysis is kept).")
      .def(
          "penalty",
          [](const ArapSolver& s, const py::object& U, const py::object& soft_targets) {
            const Eigen::Index soft_count = without_gil(s, [](const ArapData& d) { return d.soft.size(); });
            const Eigen::MatrixXd T = to_points(soft_targets, "soft_targets", true, soft_count, "#soft");
            return on_positions(
                s, U, [&](const ArapData& d, const Eigen::MatrixXd& P) { return arap_penalty(d, T, P); });
          },
          py::arg("U"), py::arg("soft_targets"),
          "sum_k W_k |c_k^T U - t_k|^2: the soft constraints' penalty at U (#V, 3); energy(U) + penalty is "
          "the "
          "total the solve minimizes.");
}

// What the last solve and the precomputation left: report, rotations and the factorization's state.
void def_results(py::class_<ArapSolver>& arap) {
  arap.def_property_readonly("report", &report_py,
                             R"(The last solve as a dict (None before the first solve): iterations, converged,
initial_energy, penalty and arap_energy (the two parts of the last energy; penalty 0 without soft
constraints), energies (float64 (iterations,), energy after each iteration), local_ms, global_ms,
local_ms_per_iteration, global_ms_per_iteration, accelerator, initial_gradient_norm, gradient_norms (per
iteration), accepted (bool per iteration: the accelerated iterate was kept), rejected, solves, accelerator_ms,
elapsed_ms (per iteration, since the start), stop_reason, potential, newton_trust_radius and
newton_reference_gradient (Newton's state after the solve), solve_ms (the whole C++ solve), and the precomputation's
intrinsic_ms, assembly_ms, factor_ms, analyze_ms (the symbolic analysis, on its own thread beside
intrinsic_ms + assembly_ms when threads > 1). Times in milliseconds.)")
      .def_property_readonly(
          "rotations", &rotations_py,
          "float64 (#cells, 3, 3): the rotation of each vertex's cell (then of each point inserted by "
          "refine_boundary) fitted to the last solution (identities before the first solve).")
      .def_property_readonly(
          "method",
          [](const ArapSolver& s) {
            return arap_method_name(without_gil(s, [](const ArapData& d) { return d.method; }));
          },
          "The energy: \"iarap\", \"spokes-rims\" or \"arap\".")
      .def_property_readonly(
          "factorization",
          [](const ArapSolver& s) {
            return factorization_name(
                without_gil(s, [](const ArapData& d) { return arap_factorization(d); }));
          },
          "The factorization L_ff got: \"cholmod-supernodal-llt\", \"simplicial-ldlt\" or \"empty\".")
      .def_property_readonly("factorizations", &ArapSolver::factorizations,
                             "How many times L_ff was factorized (1 after construction, +1 per new `fixed`).")
      .def_property_readonly(
          "pinned",
          [](const ArapSolver& s) {
            return to_numpy(without_gil(s, [](const ArapData& d) { return Eigen::VectorXi(d.pinned); }));
          },
          "(#pinned,) vertices pinned by pin_unconstrained_components (empty otherwise).")
      .def_property_readonly(
          "min_weight",
          [](const ArapSolver& s) { return without_gil(s, [](const ArapData& d) { return d.min_weight; }); },
          "The smallest element weight w_e (original ARAP and spokes-and-rims: a cotangent, negative on "
          "non-Delaunay edges; iARAP: >= 0 up to roundoff).")
      .def_property_readonly(
          "intrinsic", &intrinsic_py,
          "Summary of the intrinsic Delaunay triangulation (iarap only; zeros otherwise): "
          "flips, non_delaunay_before, non_delaunay_after, mollify_delta, intrinsic_edges, "
          "segments, tufted_cover (built on the tufted cover: the mesh is not an oriented manifold), "
          "cover_vertices.");
}

// Evaluations at given positions: energy, cell_energy, gradient, the system matrix.
void def_evaluations(py::class_<ArapSolver>& arap) {
  arap.def(
          "energy",
          [](const ArapSolver& s, const py::object& U) {
            return on_positions(
                s, U, [](const ArapData& d, const Eigen::MatrixXd& P) { return arap_energy(d, P); });
          },
          py::arg("U"), "The energy of positions U (#V, 3), minimized over rotations (squared mesh units).")
      .def(
          "cell_energy",
          [](const ArapSolver& s, const py::object& U) {
            return to_numpy(on_positions(
                s, U, [](const ArapData& d, const Eigen::MatrixXd& P) { return arap_cell_energy(d, P); }));
          },
          py::arg("U"),
          "float64 (#cells,): the energy of each cell (vertices, then points inserted by refine_boundary) at "
          "U "
          "(#V, 3); they sum to energy(U).")
      .def(
          "gradient",
          [](const ArapSolver& s, const py::object& U) {
            return to_numpy(on_positions(
                s, U, [](const ArapData& d, const Eigen::MatrixXd& P) { return arap_gradient(d, P); }));
          },
          py::arg("U"), "float64 (#V, 3): dE/dU at U (#V, 3) (Eq. 14).")
      .def(
          "system_matrix",
          [](const ArapSolver& s) {
            return to_csr(without_gil(s, [](const ArapData& d) { return arap_system_matrix(d); }));
          },
          "scipy.sparse.csr_matrix (#V, #V): the matrix L of the global step.")
      .def("__repr__", [](const ArapSolver& s) {
        return without_gil(s, [](const ArapData& d) {
          return "<iarap.ARAP " + arap_method_name(d.method) + ", " + std::to_string(d.V.rows()) +
                 " vertices, " + std::to_string(d.F.rows()) + " faces, " + std::to_string(d.fixed.size()) +
                 " fixed>";
        });
      });
}

} // namespace

void bind_arap(py::module_& m) {
  py::class_<ArapSolver> arap(m, "ARAP", R"(As-rigid-as-possible deformation of a triangle mesh.

Set up once per constrained set, solve for many targets:

    solver = iarap.ARAP(V, F, fixed=handles, method="iarap")
    U = solver.solve(targets)            # targets[k] is where vertex fixed[k] goes
    solver.report["energies"]            # energy after each iteration

Methods: "iarap" (intrinsic ARAP, paper Eq. 9), "spokes-rims" (Chao et al. 2010, Eq. 2), "arap" (Sorkine
and Alexa 2007, Eq. 1). New targets reuse the factorization of L_ff; assigning `fixed` refactorizes.
Energies are in squared mesh units. Methods release the GIL; one solver serves one thread at a time.)");
  arap.def(py::init(&make_solver), py::arg("V"), py::arg("F"), py::arg("fixed"), py::arg("method") = "iarap",
           py::kw_only(), py::arg("pin_unconstrained_components") = false, py::arg("refine_boundary") = true,
           py::arg("soft_vertices") = py::none(), py::arg("soft_weights") = py::none(),
           py::arg("soft_faces") = py::none(), py::arg("soft_barycentric") = py::none(),
           py::arg("soft_face_weights") = py::none(), py::arg("hard_faces") = py::none(),
           py::arg("hard_barycentric") = py::none(), py::arg("stiffness") = py::none(),
           py::arg("rigid_groups") = py::none(),
           R"(Precomputes the elements of `method`, the system matrix L and the factorization of L_ff.

V: (#V, 3) rest positions, or (#V, 2) for a planar mesh, deformed in its plane with rotations about z
(targets, U0, results, energy and gradient arguments then have 2 columns). F: (#F, 3) faces of a manifold, consistently oriented triangle mesh (boundary
allowed), or (#T, 4) tetrahedra (read_tet_mesh): volumetric ARAP, sum over tetrahedra of vol |F_t - R_t|^2
with one rotation per tetrahedron (`rotations`: #T, padded to #V with identities on meshes with fewer
tetrahedra than vertices); method must be "iarap" (the default; the surface energies are refused), and
soft_faces / hard_faces index tet_boundary_faces(T). fixed: (#fixed,) distinct constrained vertex indices. pin_unconstrained_components: pin the first
vertex of every connected component without a constrained vertex (else such a component raises SolverError).
refine_boundary ("iarap" only, not in the paper): split boundary edges opposite an obtuse intrinsic angle, so
that no weight is negative; the inserted points get rotation cells of their own (rows #V.. of `rotations`).
Soft constraints (issue 32): soft_vertices (#sv,) with soft_weights (#sv,) W > 0, and points on faces:
soft_faces (#sb,), soft_barycentric (#sb, 3) rows summing to 1, soft_face_weights (#sb,). The solve then
minimizes E_ARAP + sum_k W_k |c_k^T U - t_k|^2 (c_k: the vertex, or B0, B1, B2 at the face's corners); the
soft vertices stay free, and `fixed` may be empty when every component has a soft point.
Hard points on faces: hard_faces (#hb,) and hard_barycentric (#hb, 3): the solve keeps each point exactly on
its target (the last #hb rows of soft_targets), by a Schur complement on the factorized system; a point that
contradicts others (the same point, or one whose corners are all fixed, sent elsewhere) raises ValueError
naming both.
stiffness: (#V,) factors s_i > 0 on the energy of vertex i's rotation cell (issue 45): a stiffer region bends
and stretches less (None, or 1 everywhere: the energy without it, bit for bit). Ratios above about 100 make
the iteration converge slowly; L-BFGS and Newton cope best.
rigid_groups: a sequence of groups, each a sequence of at least 2 vertex indices (no vertex in two groups):
each group moves as one rigid body, exactly (issue 45), with every accelerator (a group is one body of
6 degrees of freedom; rotation_smoothing with groups raises ValueError). A group with one fixed vertex
turns about it; with more, it follows their targets, which must be a rigid motion (ValueError otherwise).
Raises ValueError (InputError, TopologyError) for bad arrays, indices, weights or meshes; SolverError (a
RuntimeError) for an unconstrained component or a failed factorization.)");
  def_solve(arap);
  def_constraints(arap);
  def_results(arap);
  def_evaluations(arap);
  m.attr("ARAP_METHODS") = py::make_tuple("iarap", "spokes-rims", "arap");
  m.attr("SOLVE_OPTIONS") = solve_option_table();
}

} // namespace iarap::python
