// The rotation cells of a per-vertex ARAP energy (original ARAP's edges or iARAP's segments,
// arap_elements.h) laid flat for a UV map: each element's rest vector drawn in the tangent plane of each
// cell that compares against it, so that a 2x2 rotation per vertex can be fitted to it.
//
// E(UV) = min_R sum_e sum_{c in cells(e)} (w_e / 2) ||UV^T b_e - R_c s_ec||^2, R_c in SO(2), with s_ec the
// rest vector s_hat_e = V^T b_e expressed in cell c's tangent frame (t1, t2, unit normal n = the
// area-weighted normal of c's faces, t1 x t2 = n) and scaled back to the length of s_hat_e: on a planar
// mesh s_ec is s_hat_e itself (in the plane's coordinates), elsewhere a flattening of the cell that keeps
// every element's length. The weights are those of the 3D energy (negative ones included, never clamped).
//
// Not the solver's planar mode (ArapOptions::planar), which deforms a mesh lying in z = 0 with one rest
// vector s_hat_e per element: here each cell of a curved surface is flattened into its own tangent plane, so
// an element has a different flat rest vector s_ec in each of its cells, which ArapElements cannot carry.
// On a planar mesh the two agree (tests/param/planar_cells_test.cpp).
#pragma once
#include "iarap/solver/arap_elements.h"

#include <Eigen/Core>
#include <Eigen/SparseCore>

namespace iarap {

struct PlanarCells {
  ArapElements elements; // b, w and cells as arap_edge_elements or iarap_elements built them
  Eigen::MatrixXd s;     // #pairs x 2: s_ec for element e, cell elements.cell[k], row k (cell_start order)
  Eigen::MatrixXd frame; // #V x 6: t1 (columns 0-2) and t2 (3-5) of each vertex's tangent frame
};

// Lays the cells of `elements` (built on V #V x 3, F #F x 3; every cell a vertex: iarap_elements without
// refine_boundary) flat. Throws InputError when elements has cells that are not vertices or when a vertex
// has no face with an area (no normal).
PlanarCells planar_cells(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, ArapElements elements);

// E(UV) for UV #V x 2; R (#V x 4, row by row) gets the minimizing rotations (closest_rotation_2d of each
// cell's covariance sum_e (w_e / 2) (UV^T b_e) s_ec^T).
double planar_cell_energy(const PlanarCells& cells, const Eigen::MatrixXd& UV, Eigen::MatrixXd& R);
double planar_cell_energy(const PlanarCells& cells, const Eigen::MatrixXd& UV);
// The energy with the rotations R (#V x 4, row by row) held instead of fitted.
double planar_cell_energy_at(const PlanarCells& cells, const Eigen::MatrixXd& UV, const Eigen::MatrixXd& R);
// S (#V x 4, row by row): each cell's covariance sum_e (w_e / 2) (UV^T b_e) s_ec^T, linear in UV (the
// rotations are closest_rotation_2d of its rows; Newton's Hessian products take it of a direction).
void planar_cell_covariances(const PlanarCells& cells, const Eigen::MatrixXd& UV, Eigen::MatrixXd& S);

// r (#V x 2) = sum_e sum_{c in cells(e)} (w_e / 2) b_e (R_c s_ec)^T, so that grad E = 2 (M UV - r) with
// M = element_system_matrix(elements) / 2: the global step solves M UV = r.
void planar_cell_rhs(const PlanarCells& cells, const Eigen::MatrixXd& R, Eigen::MatrixXd& r);

} // namespace iarap
