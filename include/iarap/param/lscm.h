// Least-squares conformal maps (Levy et al. 2002): the free-boundary initial map of ARAP parameterization.
#pragma once
#include "iarap/param/disk_mesh.h"
#include "iarap/param/param_options.h"

#include <Eigen/Core>

namespace iarap {

// The default pins of LSCM: the two boundary vertices farthest apart in space (exact search up to 4096
// boundary vertices, a double sweep from the first boundary vertex beyond), at (0, 0) and (d, 0) with d their
// distance, so that the map starts near the surface's scale.
UvPins lscm_pins(const DiskMesh& disk);

// The #V x 2 map minimizing sum_f area_f ((a - d)^2 + (b + c)^2) for J_f = [a b; c d] (the conformal
// energy: zero exactly where J_f is a similarity), with `pins` held: two or more of them, since two fix the
// map's translation, rotation and scale (the energy's null space). One sparse factorization of the
// 2 (#V - #pins) free unknowns. Throws InputError for fewer than two pins and for what check_uv_pins
// refuses, SolverError when the system cannot be factorized.
Eigen::MatrixXd lscm(const DiskMesh& disk, const UvPins& pins);

// lscm(disk, lscm_pins(disk)).
Eigen::MatrixXd lscm(const DiskMesh& disk);

} // namespace iarap
