// Least-squares conformal maps (Levy et al. 2002): the free-boundary initial map of ARAP parameterization.
#pragma once
#include "iarap/param/disk_mesh.h"

#include <Eigen/Core>

namespace iarap {

// Two vertices pinned in UV: the map's translation, rotation and scale, the conformal energy's null space.
struct UvPins {
  Eigen::Vector2i vertices; // two distinct vertex indices
  Eigen::Matrix2d uv;       // row p: the UV position of vertices(p)
};

// The default pins: the two boundary vertices farthest apart in space (exact search up to 4096 boundary
// vertices, a double sweep from the first boundary vertex beyond), at (0, 0) and (d, 0) with d their
// distance, so that the map starts near the surface's scale.
UvPins lscm_pins(const DiskMesh& disk);

// The #V x 2 map minimizing sum_f area_f ((a - d)^2 + (b + c)^2) for J_f = [a b; c d] (the conformal
// energy: zero exactly where J_f is a similarity), with `pins` held. One sparse factorization of the
// 2#V - 4 free unknowns. Throws InputError for pins out of range or equal, SolverError when the
// system cannot be factorized.
Eigen::MatrixXd lscm(const DiskMesh& disk, const UvPins& pins);

// lscm(disk, lscm_pins(disk)).
Eigen::MatrixXd lscm(const DiskMesh& disk);

} // namespace iarap
