// Writing a UV map: an OBJ with texture coordinates, or plain `u v` lines.
#pragma once
#include "iarap/io/read_obj_textured.h"

#include <Eigen/Core>
#include <string>

namespace iarap {

// By the extension, case-insensitive: .obj writes the input's `v x y z` lines, one `vt u v` per vertex and
// faces `f a/a b/b c/c`; .txt writes one `u v` line per vertex. Numbers printed with %.17g (round-trip
// exact). Written atomically (a temporary file renamed over `path`). Throws InputError for another
// extension, shapes that disagree (V #V x 3, F #F x 3 with indices in range, UV #V x 2), or an I/O failure,
// naming the path.
void write_uv_map(const std::string& path, const Eigen::MatrixXd& V, const Eigen::MatrixXi& F,
                  const Eigen::MatrixXd& UV);

} // namespace iarap

namespace iarap {

// An atlas's UV map, per corner (corner_uv (3 #F) x 2, row 3 f + k for corner k of face f): .obj writes
// the input's `v` lines in order, one `vt` per distinct (vertex, uv) pair in order of first use (a vertex
// on a seam has one per chart) and the faces in order, `f a/ta b/tb c/tc`; .txt writes one `u v` line per
// corner. Atomic; throws InputError as write_uv_map does.
void write_uv_atlas(const std::string& path, const Eigen::MatrixXd& V, const Eigen::MatrixXi& F,
                    const Eigen::MatrixXd& corner_uv);

// The same on the input's own face lines (read_obj_textured's polygons, whose fans are the triangles F in
// order): .obj writes `f a/ta b/tb c/tc d/td ...` per polygon, in order; .txt one `u v` line per polygon
// corner. A polygon corner takes the UV of its triangle corner in the first of its triangles that lies in
// a chart (chart(f) >= 0; uv_atlas keeps a polygon's triangles in one chart, so they agree). InputError as
// write_uv_atlas, and for polygons whose fans are not F's count or a chart vector of another size.
void write_uv_atlas_polygons(const std::string& path, const Eigen::MatrixXd& V, const Eigen::MatrixXi& F,
                             const Eigen::MatrixXd& corner_uv, const Eigen::VectorXi& chart,
                             const ObjPolygons& polygons);

} // namespace iarap
