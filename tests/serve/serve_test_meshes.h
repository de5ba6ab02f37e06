// Small meshes built in code for the server's tests, and what the tests read of them.
#pragma once
#include "iarap/io/read_mesh.h"

#include <string>

namespace iarap::test {

// A (columns + 1) x (rows + 1) grid of the rectangle [0, width] x [0, 1], two triangles per cell, vertex
// (i, j) at index j * (columns + 1) + i. z = lift * x^2 / width^2 (0: the plane z = 0).
MeshData grid_mesh(int columns, int rows, double width, double lift = 0);

// The vertices of grid column i (bottom to top).
Eigen::VectorXi grid_column(int columns, int rows, int i);

// The rows of X listed in index, in that order.
Eigen::MatrixXd rows_of(const Eigen::MatrixXd& X, const Eigen::VectorXi& index);

// Whether text holds part (error messages).
bool contains(const std::string& text, const std::string& part);

} // namespace iarap::test
