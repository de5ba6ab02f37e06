// The charts a file's texture coordinates already define (`iarap param --charts keep`).
#pragma once
#include <Eigen/Core>
#include <vector>

namespace iarap {

// The charts of a triangle mesh F (#F x 3) whose corners have texture indices FT (#F x 3, read_obj_textured):
// the connected components of the faces glued along the edges whose two faces give both ends the same
// texture indices (an edge where they differ is a seam). Returns #F chart ids 0..n-1, numbered in order of
// the first face. Throws InputError when FT is not #F x 3 or a face has a corner without a texture index
// (naming the face).
std::vector<int> texture_seam_charts(const Eigen::MatrixXi& F, const Eigen::MatrixXi& FT);

} // namespace iarap
