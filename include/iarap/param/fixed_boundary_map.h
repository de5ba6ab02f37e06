// Maps with the boundary fixed on a circle and every inner vertex at a weighted average of its neighbours:
// Tutte's embedding (uniform weights) and the harmonic map (cotan weights).
#pragma once
#include "iarap/param/disk_mesh.h"
#include "iarap/param/param_options.h"

#include <Eigen/Core>

namespace iarap {

enum class BoundaryMapWeights {
  Uniform, // Tutte (1963), Floater (2003): injective for any disk with a convex boundary
  Cotan,   // harmonic (Pinkall and Polthier 1993): closer to conformal, may flip where weights are negative
};

// #boundary x 2: the boundary loop on a circle centred at the origin, each vertex at the angle 2 pi s / S
// (s its arc length along the loop from the first vertex, S the loop's length), counter-clockwise in the
// loop's order; radius sqrt(area / pi), so that the disk has the surface's area.
Eigen::MatrixXd circle_boundary(const DiskMesh& disk);

// The #V x 2 map with boundary vertex disk.boundary[p] at boundary_uv.row(p) (#boundary x 2) and the
// inner vertices solving L_II U_I = -L_IB U_B for the chosen weights; inner_pins, inner vertices held at
// their UV positions too (Tutte's injectivity guarantee does not extend to them). Throws InputError when
// boundary_uv has the wrong shape, for what check_uv_pins refuses and for a pin on the boundary, and
// SolverError when the system cannot be factorized.
Eigen::MatrixXd fixed_boundary_map(const DiskMesh& disk, BoundaryMapWeights weights,
                                   const Eigen::MatrixXd& boundary_uv, const UvPins& inner_pins = {});

} // namespace iarap
