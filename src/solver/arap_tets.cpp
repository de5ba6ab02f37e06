#include "iarap/solver/arap_tets.h"

#include "iarap/core/errors.h"
#include "iarap/core/stopwatch.h"
#include "iarap/io/tet_mesh.h"
#include "iarap/mesh/connected_components.h"
#include "iarap/solver/arap.h"

#include "cell_stiffness.h"
#include "constraint_layout.h"
#include "rigid_groups.h"
#include "soft_terms.h"

#include <string>

namespace iarap {

namespace {

// T with every negative tetrahedron reoriented (c and d swapped), for outward boundary faces.
Eigen::MatrixXi positive_tets(const Eigen::MatrixXd& V, const Eigen::MatrixXi& T) {
  Eigen::MatrixXi P = T;
  const Eigen::VectorXd volume = tet_signed_volumes(V, T);
  for (Eigen::Index t = 0; t < T.rows(); ++t)
    if (volume(t) < 0) std::swap(P(t, 2), P(t, 3));
  return P;
}

// Components over the tetrahedra: the triangles (a, b, c) and (a, d, d) of each join its four corners.
Eigen::VectorXi tet_components(const Eigen::MatrixXi& T, int n, int* count) {
  Eigen::MatrixXi joins(2 * T.rows(), 3);
  joins << T.leftCols(3), T.col(0), T.col(3), T.col(3);
  return vertex_components(joins, n, count);
}

// The factor of each tetrahedron's cell: the mean of its corners' (padding cells: 1).
Eigen::VectorXd tet_cell_stiffness(const ArapElements& el, const Eigen::MatrixXi& T,
                                   const Eigen::VectorXd& s) {
  Eigen::VectorXd cell = Eigen::VectorXd::Ones(el.num_cells);
  for (Eigen::Index t = 0; t < T.rows(); ++t)
    cell(t) = (s(T(t, 0)) + s(T(t, 1)) + s(T(t, 2)) + s(T(t, 3))) / 4.0;
  return cell;
}

void check_tet_options(const ArapOptions& options) {
  if (options.method != ArapMethod::Iarap)
    throw InputError(
        "tet ARAP: method '" + arap_method_name(options.method) +
        "' is a surface energy; a tetrahedral mesh has one energy (one rotation per tetrahedron, "
        "the cotangent weights of its edges): per-vertex spokes on a volume mesh drift from rest "
        "where weights are negative. Use the default method");
  if (options.planar) throw InputError("tet ARAP: ArapOptions::planar is for flat triangle meshes");
}

} // namespace

ArapData arap_precompute_tets(const Eigen::MatrixXd& V, const Eigen::MatrixXi& T,
                              const Eigen::VectorXi& fixed, const ArapOptions& options) {
  return arap_precompute_tets(V, T, fixed, ArapSoftConstraints{}, options);
}

ArapData arap_precompute_tets(const Eigen::MatrixXd& V, const Eigen::MatrixXi& T,
                              const Eigen::VectorXi& fixed, const ArapSoftConstraints& soft,
                              const ArapOptions& options) {
  check_tet_options(options);
  const auto start = Clock::now();
  ArapElements elements = tet_arap_elements(V, T); // checks V and T
  const int n = static_cast<int>(V.rows());
  ArapData data;
  data.method = ArapMethod::Iarap;
  data.pin_unconstrained_components = options.pin_unconstrained_components;
  data.V = V;
  data.F = tet_boundary_faces(positive_tets(V, T));
  data.component = tet_components(T, n, &data.component_count);
  detail::check_soft_constraints(soft, n, data.F, fixed);
  if (options.stiffness.size() > 0) check_arap_stiffness(options.stiffness, V.rows());
  detail::ConstraintLayout layout = detail::constraint_layout(data, fixed, soft);
  if (!detail::is_unit_stiffness(options.stiffness))
    detail::apply_cell_stiffness(elements, tet_cell_stiffness(elements, T, options.stiffness));
  data.elements = std::move(elements);
  data.L = element_system_matrix(data.elements);
  data.timings.assembly_ms = ms_since(start);
  const auto factor_start = Clock::now();
  data.Q = detail::soft_system_matrix(detail::soft_points(soft, data.F), n);
  Eigen::SparseMatrix<double> L_ff, L_fc;
  detail::split_system(detail::with_soft(data.L, data.Q), layout, L_ff, &L_fc);
  SparseCholesky solver;
  solver.set_ordering(options.ordering);
  solver.factorize(L_ff); // throws SolverError
  if (!options.rigid_groups.empty())
    data.rigid = detail::rigid_group_system(options.rigid_groups, data, data.Q, soft, fixed, layout);
  detail::commit_layout(data, fixed, layout, solver, L_fc);
  data.soft = soft;
  data.R.assign(static_cast<size_t>(data.elements.num_cells), Eigen::Matrix3d::Identity());
  data.timings.factor_ms = ms_since(factor_start);
  return data;
}

} // namespace iarap
