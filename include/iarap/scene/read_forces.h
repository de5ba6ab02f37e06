// Reader of per-vertex forces files (iarap deform / simulate --forces): one force per line.
//
// Format, blank-separated, 0-based vertex indices (file order of the mesh):
//   INDEX FX FY FZ     a constant force on vertex INDEX, in mass x mesh units / time^2
// '#' starts a comment running to the end of the line; blank lines are skipped; lines naming one vertex
// add up. Vertices not named get no force.
#pragma once
#include <Eigen/Core>

#include <istream>
#include <string>

namespace iarap {

// The #V x 3 forces of a mesh with num_vertices vertices from the file at path. Throws InputError naming
// "path:line" for an unreadable file, a line without exactly four tokens, a bad or out-of-range index
// (the message gives the mesh size), a component that is not a finite number, and a file with no force.
Eigen::MatrixXd read_forces(const std::string& path, int num_vertices);

// Same, from a stream; source names the input in messages.
Eigen::MatrixXd parse_forces(std::istream& in, const std::string& source, int num_vertices);

} // namespace iarap
