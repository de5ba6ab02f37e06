// Writing a UV map: an OBJ with texture coordinates, or plain `u v` lines.
#pragma once
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

} // namespace iarap
