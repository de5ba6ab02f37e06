// Internal: what the OBJ, OFF and PLY writers share: the argument check and exact number formatting.
#pragma once
#include <Eigen/Core>
#include <string>

namespace iarap::io_detail {

// Throws InputError unless V is #V x 3 and F is #F x 3 with indices in 0..#V-1 (names the first bad face).
void check_mesh_arrays(const std::string& path, const Eigen::MatrixXd& V, const Eigen::MatrixXi& F);

// Appends "%.17g" of x (round-trip exact for doubles).
void append_double(std::string& out, double x);

// Appends the decimal integer i.
void append_int(std::string& out, long long i);

// One text line per row of V: prefix, then the three coordinates (%.17g) separated by spaces.
void append_vertex_lines(std::string& out, const Eigen::MatrixXd& V, const char* prefix);

// One text line per row of F: prefix, then the three indices plus index_base, separated by spaces.
void append_face_lines(std::string& out, const Eigen::MatrixXi& F, const char* prefix, int index_base);

} // namespace iarap::io_detail
