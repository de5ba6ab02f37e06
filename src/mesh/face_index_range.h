// The range check of face indices, written once for every function that takes F: the message names the
// face, the index and the vertex count ("face 812 uses vertex 9001; mesh has 5000 vertices").
#pragma once
#include <Eigen/Core>
#include <string>

namespace iarap {

// "face <face> uses vertex <index>; mesh has <vertex_count> vertices".
std::string out_of_range_face_index(Eigen::Index face, Eigen::Index index, Eigen::Index vertex_count);

// Throws InputError, `context` followed by out_of_range_face_index, for the first entry of F (#F x 3) from
// face first_face on outside 0..vertex_count-1; F's column count is the caller's to check.
void require_face_indices_in_range(const Eigen::Ref<const Eigen::MatrixXi>& F, Eigen::Index vertex_count,
                                   const std::string& context = "", Eigen::Index first_face = 0);

// Throws InputError, "<function>: V has 2 columns; 3 needed" (or F), or as require_face_indices_in_range
// with "<function>: ", unless V is #V x 3 and F #F x 3 with every index in range.
void require_triangle_mesh(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, const std::string& function);

} // namespace iarap
