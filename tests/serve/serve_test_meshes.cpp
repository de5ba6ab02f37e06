#include "serve_test_meshes.h"

namespace iarap::test {

MeshData grid_mesh(int columns, int rows, double width, double lift) {
  MeshData mesh;
  const int stride = columns + 1;
  mesh.V.resize((rows + 1) * stride, 3);
  for (int j = 0; j <= rows; ++j) {
    for (int i = 0; i <= columns; ++i) {
      const double x = width * i / columns;
      mesh.V.row(j * stride + i) << x, static_cast<double>(j) / rows, lift * x * x / (width * width);
    }
  }
  mesh.F.resize(2 * columns * rows, 3);
  int f = 0;
  for (int j = 0; j < rows; ++j) {
    for (int i = 0; i < columns; ++i) {
      const int a = j * stride + i, b = a + 1, c = a + stride, d = c + 1;
      mesh.F.row(f++) << a, b, d;
      mesh.F.row(f++) << a, d, c;
    }
  }
  return mesh;
}

Eigen::VectorXi grid_column(int columns, int rows, int i) {
  Eigen::VectorXi column(rows + 1);
  for (int j = 0; j <= rows; ++j) column[j] = j * (columns + 1) + i;
  return column;
}

Eigen::MatrixXd rows_of(const Eigen::MatrixXd& X, const Eigen::VectorXi& index) {
  Eigen::MatrixXd out(index.size(), X.cols());
  for (Eigen::Index k = 0; k < index.size(); ++k) out.row(k) = X.row(index[k]);
  return out;
}

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

} // namespace iarap::test
