// Volumetric deformation of a closed surface (`iarap deform --volume`, issue 45 item 3): its inside is
// tetrahedralized, the tetrahedra are deformed by tet ARAP (arap_tets.h) under the surface's constraints,
// and the surface comes back with its own vertices and faces.
//
// The tetrahedralization is TetGen's (Debian's `tetgen` 1.5 program), run as an external program: TetGen is
// AGPL, this project MIT, so it is neither linked nor vendored; without the program the feature is refused
// with a message saying how to install it. Its switches -pY keep the surface: every input vertex is a tet
// vertex, in the input's order and at its exact coordinates (TetGen writes 17 significant digits), and the
// boundary faces of the tetrahedra are the input's faces, so the surface is read back as the first #V rows of
// the result with the input's F. -q adds interior points for quality (radius-edge ratio 2).
#pragma once
#include "iarap/io/tet_mesh.h"
#include "iarap/jobs/deform_job.h"

#include <Eigen/Core>

#include <string>

namespace iarap {

struct TetgenOptions {
  std::string program = "tetgen"; // looked up on PATH
  std::string switches = "pYqQ";  // PLC, keep the surface, quality, quiet
};

// The tetrahedra of the inside of the closed surface (V #V x 3, F #F x 3): TetMesh with V's rows first,
// bit for bit, then TetGen's interior points; its boundary faces are F's (as a set). Throws InputError when
// the program cannot be run (naming it and the Debian package), when it fails (its exit status or signal
// and the last lines it printed: e.g. a self-intersecting surface), or when its output does not keep the
// surface (a vertex moved or renumbered, a boundary face count unlike #F).
TetMesh tetrahedralize_inside(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F,
                              const TetgenOptions& options = {});

// The volume a closed, consistently oriented triangle surface encloses: sum over faces of
// det(a, b, c) / 6 (positive when the faces point outward).
double enclosed_volume(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F);

// The tetrahedral scene of a surface scene: surface.mesh tetrahedralized (tetrahedralize_inside), the
// constraints (indices of surface vertices, which keep their numbers), forces (0 on interior points),
// stiffness (1 on interior points) and rigid groups carried over. Throws InputError for a surface that is
// not closed (boundary edges) and for soft or hard points on faces (they index the surface's faces; give
// vertices), and what tetrahedralize_inside throws.
DeformScene volume_scene(const DeformScene& surface, const TetgenOptions& options = {});

} // namespace iarap
