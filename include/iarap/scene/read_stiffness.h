// Reader of per-vertex stiffness files (iarap deform --stiffness, ArapOptions::stiffness): one factor per
// line.
//
// Format, blank-separated, 0-based vertex indices (file order of the mesh):
//   INDEX S     the energy of vertex INDEX's rotation cell is multiplied by S (finite, > 0)
// '#' starts a comment running to the end of the line; blank lines are skipped. Vertices not named keep 1.
#pragma once
#include <Eigen/Core>

#include <istream>
#include <string>

namespace iarap {

// The #V factors of a mesh with num_vertices vertices from the file at path. Throws InputError naming
// "path:line" for an unreadable file, a line without exactly two tokens, a bad or out-of-range index (the
// message gives the mesh size), a factor that is not a finite number > 0, a vertex named twice (both
// lines), and a file with no factor.
Eigen::VectorXd read_stiffness(const std::string& path, int num_vertices);

// Same, from a stream; source names the input in messages.
Eigen::VectorXd parse_stiffness(std::istream& in, const std::string& source, int num_vertices);

} // namespace iarap
