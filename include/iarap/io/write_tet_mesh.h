// Writing tetrahedral meshes as MEDIT ASCII .mesh, atomically and at full precision (as write_mesh.h).
#pragma once
#include <Eigen/Core>

#include <string>

namespace iarap {

// MeshVersionFormatted 2, Dimension 3, Vertices (%.17g, reference 0), Tetrahedra (1-based, reference 0),
// End. The extension must be .mesh (any case). Throws InputError for V not #V x 3, T not #T x 4 or an
// index out of range (naming the tetrahedron), another extension, or an I/O failure (naming the path).
void write_tet_mesh(const std::string& path, const Eigen::MatrixXd& V, const Eigen::MatrixXi& T);

// True for the extension write_tet_mesh writes (.mesh, any case).
bool is_tet_mesh_output_path(const std::string& path);

} // namespace iarap
