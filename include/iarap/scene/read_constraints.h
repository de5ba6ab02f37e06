// Reader of constraints files: one constraint per line.
//
// Format, blank-separated, 0-based indices (file order of the mesh):
//   INDEX X Y Z                 a hard vertex target
//   INDEX X Y Z W               a soft vertex: penalty W |x_INDEX - (X, Y, Z)|^2, W finite and > 0
//   b FACE B0 B1 B2 X Y Z W     a soft point on face FACE = (a, b, c): penalty W |B0 x_a + B1 x_b + B2 x_c -
//                               (X, Y, Z)|^2, B finite and summing to 1 within 1e-9
// '#' starts a comment running to the end of the line; blank lines are skipped. A hard vertex listed
// twice with the same target is merged (with a warning); with different targets it is an error, and so
// is a vertex that is both hard and soft or soft twice (naming both lines). Hard points on faces
// ('b' without W) are not supported yet.
#pragma once
#include "iarap/scene/constraint_set.h"

#include <istream>
#include <string>

namespace iarap {

// Reads the constraints of a mesh with num_vertices vertices and num_faces faces from the file at path.
// Throws InputError naming "path:line" for: an unreadable file, a bad or missing token, trailing
// tokens, a non-finite coordinate, an index or face out of range (the message gives the mesh size), a
// weight that is not finite and > 0, barycentric coordinates not summing to 1, a 'b' line without weight,
// a duplicate index with a different target or of another kind (naming both lines), and a file with no
// constraint.
ConstraintSet read_constraints(const std::string& path, int num_vertices, int num_faces = 0);

// Same, from a stream; source names the input in messages (a path or e.g. "<request>").
ConstraintSet parse_constraints(std::istream& in, const std::string& source, int num_vertices,
                                int num_faces = 0);

} // namespace iarap
