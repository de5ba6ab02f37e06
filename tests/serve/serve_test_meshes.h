// Small meshes built in code for the server's tests.
#pragma once
#include "iarap/io/read_mesh.h"

namespace iarap::test {

// A (columns + 1) x (rows + 1) grid of the rectangle [0, width] x [0, 1], two triangles per cell, vertex
// (i, j) at index j * (columns + 1) + i. z = lift * x^2 / width^2 (0: the plane z = 0).
MeshData grid_mesh(int columns, int rows, double width, double lift = 0);

// The vertices of grid column i (bottom to top).
Eigen::VectorXi grid_column(int columns, int rows, int i);

} // namespace iarap::test
