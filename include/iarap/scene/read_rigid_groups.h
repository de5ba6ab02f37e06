// Reader of rigid-group files (iarap deform --rigid, ArapOptions::rigid_groups): one rigid part per line.
//
// Format, blank-separated, 0-based vertex indices (file order of the mesh):
//   I J K ...   the vertices of one group, which move as one rigid body (at least 2, each in one group)
// '#' starts a comment running to the end of the line; a line that is only a comment is skipped. A blank
// line is an error (an empty group), so that a group cannot vanish unnoticed.
#pragma once
#include <istream>
#include <string>
#include <vector>

namespace iarap {

// The groups of a mesh with num_vertices vertices from the file at path, in the file's order. Throws
// InputError naming "path:line" for an unreadable file, a blank line, a bad or out-of-range index (the
// message gives the mesh size), a group of one vertex, a vertex named twice in a line or on two lines (both
// lines), and a file with no group.
std::vector<std::vector<int>> read_rigid_groups(const std::string& path, int num_vertices);

// Same, from a stream; source names the input in messages.
std::vector<std::vector<int>> parse_rigid_groups(std::istream& in, const std::string& source,
                                                 int num_vertices);

} // namespace iarap
