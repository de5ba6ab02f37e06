// Checks that an output file can be written before the work that produces it, so that a typo in an
// output path fails in milliseconds instead of after a long solve.
#pragma once
#include <string>

namespace iarap {

// Throws InputError naming `path` when its folder does not exist, is not a folder or is not writable, or
// when `path` itself is a folder. Writes nothing.
void check_output_path(const std::string& path);

// check_output_path, and the extension must be one write_mesh writes (.obj .off .ply, any case).
void check_mesh_output_path(const std::string& path);

} // namespace iarap
