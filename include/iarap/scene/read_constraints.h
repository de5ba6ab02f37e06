// Reader of constraints files: one "index x y z" per line.
//
// Format: a 0-based vertex index (file order of the mesh) and three target coordinates per line,
// separated by blanks. '#' starts a comment running to the end of the line; blank lines are skipped.
// A vertex listed twice with the same target is merged (with a warning); with different targets it
// is an error.
#pragma once
#include "iarap/scene/constraint_set.h"

#include <istream>
#include <string>

namespace iarap {

// Reads the constraints of a mesh with num_vertices vertices from the file at path.
// Throws InputError naming "path:line" for: an unreadable file, a bad or missing token, trailing
// tokens, a non-finite coordinate, an index out of range (the message gives the mesh size), a
// duplicate index with a different target (naming both lines), and a file with no constraint.
ConstraintSet read_constraints(const std::string& path, int num_vertices);

// Same, from a stream; source names the input in messages (a path or e.g. "<request>").
ConstraintSet parse_constraints(std::istream& in, const std::string& source, int num_vertices);

} // namespace iarap
