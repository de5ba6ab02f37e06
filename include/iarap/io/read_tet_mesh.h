// Reading tetrahedral meshes from MEDIT .mesh, TetGen .node/.ele and gmsh .msh (2.2 and 4.1, ASCII),
// keeping the file's vertex order.
//
// Every reader throws InputError whose message names "path:line: ...": unreadable file, truncated data,
// a missing section, bad tokens, out-of-range indices, and the tetrahedra find_tet_problem refuses (a
// repeated vertex, zero volume) or the orientation rule of tet_mesh.h refuses (mixed signs). Counts in the
// files are never trusted for allocation before the data proves it exists. Elements other than
// tetrahedra (triangles, edges, points) are read past; a note counts them. Quadratic (10-node)
// tetrahedra keep their four corners, with a note.
#pragma once
#include "iarap/io/tet_mesh.h"

#include <string>

namespace iarap {

// Dispatches on the extension, case-insensitive: .mesh, .node or .ele (the other file of the pair beside
// it), .msh. Throws InputError for others.
TetMesh read_tet_mesh(const std::string& path);

// True for the extensions read_tet_mesh reads (.mesh .node .ele .msh, any case).
bool is_tet_mesh_path(const std::string& path);

// MEDIT ASCII: keywords case-insensitive and free-form (a count may follow on the same line or the next),
// `#` comments; `MeshVersionFormatted v`, `Dimension 3`, `Vertices n` then n x (x y z ref),
// `Tetrahedra m` then m x (a b c d ref), 1-based; other sections (Triangles, Edges, Corners, Ridges,
// Required*, Normals, Tangents, Quadrilaterals, Hexahedra, Prisms ...) read past; `End`. Vertices and
// Tetrahedra are required.
TetMesh read_medit_mesh(const std::string& path);

// TetGen: `path` is the .node or the .ele file, the other one has the same stem. .node: `n 3 attributes
// markers` then `index x y z [attributes] [marker]`; .ele: `m 4|10 attributes` then `index a b c d ...`;
// `#` comments. Indices are 0- or 1-based as the .node file's first index says.
TetMesh read_tetgen(const std::string& path);

// gmsh ASCII, format 2.2 ($Nodes, $Elements with type 4 or 11 for tetrahedra) and 4.1 (entity blocks).
// Node tags may be any positive numbers; vertices are numbered in the order of $Nodes.
TetMesh read_gmsh(const std::string& path);

} // namespace iarap
