// Reading triangle meshes from OBJ, OFF, PLY and STL files, keeping the file's vertex order.
//
// Vertex order is preserved exactly by every reader except read_stl (handle indices refer to it).
// Polygons are triangulated as a fan from their first corner, (c0, ci, ci+1); a note records how many.
// NaN and Inf coordinates load as such (check_mesh reports them). Every reader throws InputError whose
// message names "path:line: ..." for text or "path: byte offset N: ..." for binary data: unreadable file,
// truncated data, wrong counts, bad tokens, out-of-range or negative face indices, unsupported variants.
// Counts in headers are never trusted for allocation before the data proves it exists.
#pragma once
#include <Eigen/Core>
#include <string>
#include <vector>

namespace iarap {

struct MeshData {
  Eigen::MatrixXd V;              // #V x 3 positions, in file order
  Eigen::MatrixXi F;              // #F x 3 vertex indices (0-based), polygons fan-triangulated
  std::vector<std::string> notes; // what the reader changed: triangulated polygons, strips, welded vertices
};

// Dispatches on the extension, case-insensitive: .obj .off .ply .stl. Throws InputError for others.
MeshData read_mesh(const std::string& path);

// Wavefront OBJ: `v x y z [w]`, `f` with `i`, `i/t`, `i//n`, `i/t/n` corners, negative (relative) indices,
// polygons. Other statements (vt, vn, g, o, s, usemtl, mtllib, l, p) are ignored.
MeshData read_obj(const std::string& path);

// OFF (also COFF, NOFF, CNOFF, STOFF...: extra per-vertex values are ignored), ASCII only. Polygons allowed;
// trailing per-face colors ignored.
MeshData read_off(const std::string& path);

// PLY: ascii, binary_little_endian and binary_big_endian; scalar x, y, z of any numeric type in element
// `vertex`; faces from element `face` (list `vertex_indices` or `vertex_index`, any integer types) and/or
// `tristrips` (list `vertex_indices`, -1 restarts a strip, odd triangles reversed, degenerate ones skipped).
// Other elements and properties are read past and ignored.
MeshData read_ply(const std::string& path);

// STL, ASCII or binary (told apart by the binary size rule 84 + 50 * count). The one reader that renumbers:
// positions that are bitwise identical (after float -> double) are welded into one vertex, numbered by first
// appearance; a note gives the count before and after.
MeshData read_stl(const std::string& path);

} // namespace iarap
