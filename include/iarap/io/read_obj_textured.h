// Reading an OBJ with what read_obj drops and a UV atlas needs: the texture coordinates (`vt`), each face
// corner's texture index, and the face lines as written (polygons before triangulation), so that a UV map
// can be computed on the triangles and written back on the input's own polygons.
#pragma once
#include "iarap/io/read_mesh.h"

#include <Eigen/Core>
#include <string>
#include <vector>

namespace iarap {

// The face lines of an OBJ in file order: polygon p has the corners first[p] .. first[p + 1] - 1.
struct ObjPolygons {
  std::vector<int> first;   // #polygons + 1 offsets into vertex / texture
  std::vector<int> vertex;  // 0-based vertex index of each corner
  std::vector<int> texture; // 0-based vt index of each corner, -1 for a corner written without one
  int size() const { return static_cast<int>(first.size()) - 1; }
  int corners(int p) const {
    return first[static_cast<std::size_t>(p) + 1] - first[static_cast<std::size_t>(p)];
  }
};

struct TexturedObj {
  MeshData mesh;                        // exactly what read_obj returns (V, fan-triangulated F, notes)
  Eigen::MatrixXd TC;                   // #vt x 2: the `vt u v` lines in order (v is 0 when missing)
  Eigen::MatrixXi FT;                   // #F x 3: the vt index of each triangle corner, -1 without one
  std::vector<int> polygon_of_triangle; // #F: the face line (polygon index) each triangle comes from
  ObjPolygons polygons;
};

// Reads the OBJ as read_obj does (the same V, F, notes and errors), plus `vt` lines and the `t` of each
// `i/t` or `i/t/n` corner (relative indices too). Polygons are fan-triangulated from their first corner,
// n - 2 triangles each in order, so triangle corners take their polygon corners' texture indices. Throws
// InputError naming "path:line" for a bad `vt` number, a texture index that is 0, bad or names a `vt` the
// file does not have, and a face with texture indices on some corners only.
TexturedObj read_obj_textured(const std::string& path);

} // namespace iarap
