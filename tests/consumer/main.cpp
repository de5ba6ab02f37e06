// Reads a mesh with the installed library and checks that its cotan Laplacian has constants in its kernel.
#include <iarap/io/read_mesh.h>
#include <iarap/mesh/cotan.h>

#include <iostream>

int main(int argc, char** argv) {
  if (argc != 2) return 2;
  const iarap::MeshData mesh = iarap::read_mesh(argv[1]);
  const Eigen::SparseMatrix<double> L = iarap::cotan_laplacian(mesh.V, mesh.F);
  const double residual = (L * Eigen::VectorXd::Ones(L.cols())).cwiseAbs().maxCoeff();
  std::cout << "vertices " << mesh.V.rows() << " faces " << mesh.F.rows() << " |L 1| " << residual << "\n";
  // Row sums are sums of cancelling weights of size ~ max |L(i,i)|: zero up to rounding.
  return residual <= 1e-12 * L.diagonal().cwiseAbs().maxCoeff() ? 0 : 1;
}
