// Volumetric (tetrahedral) ARAP on the solver's one engine: one rotation per tetrahedron, the elements its
// six edges with their cotangent weights, so that
//   E(U) = sum_t vol_t min_{R in SO(3)} || F_t - R ||_F^2,   F_t the deformation gradient of tetrahedron t
// (the elastic energy of libigl's ARAP_ENERGY_TYPE_ELEMENTS, Chao et al. 2010). Every arap.h function
// after the precomputation works unchanged on the result: arap_solve with every accelerator (Newton
// included), arap_energy, arap_gradient, arap_set_fixed, soft constraints on the boundary faces.
//
//   TetMesh mesh = read_tet_mesh("bar.mesh");                       // io/read_tet_mesh.h
//   ArapData data = arap_precompute_tets(mesh.V, mesh.T, fixed);
//   Eigen::MatrixXd U = mesh.V;
//   ArapReport report = arap_solve(data, targets, U);
#pragma once
#include "iarap/solver/arap_types.h"

#include <Eigen/Core>

namespace iarap {

// The elements of the tetrahedral energy on the rest mesh V (#V x 3) and T (#T x 4, either orientation):
// for each tetrahedron t and each of its edges (i, j), b = e_j - e_i, s_hat = V_j - V_i, cells {t} and
//   w = 2 c_ij,  c_ij = l_kl cot(theta_kl) / 6
// (l_kl the length of the opposite edge, theta_kl the dihedral angle there), the weights for which
// vol |A|_F^2 = sum_edges c_ij |A (V_j - V_i)|^2 for every linear map A; the factor 2 is the energy's w / 2.
// Weights are negative at obtuse dihedral angles and kept (as libigl does): the per-tetrahedron sum is
// still vol |F - R|^2 >= 0. Cells: num_cells = max(#T, #V), cell t < #T the rotation of tetrahedron t;
// cells #T.. (only when a mesh has more vertices than tetrahedra) have no element and stay the identity
// (the streamed layout numbers vertices and cells in one visit order). element face = -1: these elements
// lie on no triangle, so L comes from element_system_matrix(elements), never from a face pattern.
// Throws InputError (shapes, non-finite V, an index out of range, a repeated vertex: naming the
// tetrahedron), TopologyError for a tetrahedron of zero volume (find_tet_problem's rule).
ArapElements tet_arap_elements(const Eigen::MatrixXd& V, const Eigen::MatrixXi& T);

// The precomputation of arap_precompute (arap.h) for a tetrahedral mesh: the elements above, L, the
// factorization of L_ff for `fixed` (#fixed, 0-based), connected components over the tetrahedra.
// data.F = tet_boundary_faces of T (each tetrahedron taken positive), outward: what a front-end writes as
// the surface, and what soft points on faces (ArapSoftConstraints::faces) index. Interior vertices are free
// like any other; a vertex in no tetrahedron is pinned where the initial guess puts it.
// options: method must be ArapMethod::Iarap (the default; the tetrahedral energy is the only one here):
// ArapMethod::Arap and SpokesRims are refused with InputError, since their spokes (per-vertex cells) on a
// volume mesh are the surface energies' rotations on the wrong cells and drift from rest where weights
// are negative. intrinsic is ignored; planar must be false. stiffness (#V) multiplies each tetrahedron's
// energy by the mean of its four vertices' factors. Throws as tet_arap_elements, and as arap_precompute
// for fixed, soft constraints, stiffness and the factorization.
ArapData arap_precompute_tets(const Eigen::MatrixXd& V, const Eigen::MatrixXi& T,
                              const Eigen::VectorXi& fixed, const ArapOptions& options = {});
ArapData arap_precompute_tets(const Eigen::MatrixXd& V, const Eigen::MatrixXi& T,
                              const Eigen::VectorXi& fixed, const ArapSoftConstraints& soft,
                              const ArapOptions& options = {});

} // namespace iarap
