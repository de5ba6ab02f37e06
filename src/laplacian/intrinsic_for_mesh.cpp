#include "intrinsic_for_mesh.h"

#include "iarap/core/errors.h"

#include <string>

namespace iarap::detail {

namespace {

void require(bool ok, const std::string& what) {
  if (!ok) throw InputError("precomputed intrinsic Delaunay triangulation does not match the mesh: " + what);
}

} // namespace

const IntrinsicDelaunay& intrinsic_for_mesh(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F,
                                            const IntrinsicDelaunay* precomputed,
                                            std::optional<IntrinsicDelaunay>& storage) {
  if (!precomputed) {
    storage = intrinsic_delaunay(V, F);
    return *storage;
  }
  const IntrinsicTriangulation& T = precomputed->triangulation;
  const auto num_edges = static_cast<size_t>(T.E.rows());
  require(T.F.rows() == F.rows(),
          "it has " + std::to_string(T.F.rows()) + " faces, the mesh " + std::to_string(F.rows()));
  require(T.E.cols() == 2 && T.length.size() == T.E.rows() && T.cot_weight.size() == T.E.rows() &&
              T.FE.rows() == T.F.rows(),
          "its edge arrays disagree in size (#E = " + std::to_string(T.E.rows()) + ")");
  require(precomputed->traces.start.size() == num_edges + 1,
          "traces cover " + std::to_string(precomputed->traces.start.size()) + " offsets for " +
              std::to_string(num_edges) + " edges");
  require(static_cast<size_t>(precomputed->segments.edge_start.size()) == num_edges + 1,
          "segments cover " + std::to_string(precomputed->segments.edge_start.size()) + " offsets for " +
              std::to_string(num_edges) + " edges");
  require(precomputed->segments.B.cols() == V.rows(),
          "segment matrix B has " + std::to_string(precomputed->segments.B.cols()) + " columns, the mesh " +
              std::to_string(V.rows()) + " vertices");
  for (Eigen::Index e = 0; e < T.E.rows(); ++e)
    for (int k = 0; k < 2; ++k)
      require(T.E(e, k) >= 0 && T.E(e, k) < V.rows(), "intrinsic edge " + std::to_string(e) +
                                                          " uses vertex " + std::to_string(T.E(e, k)) +
                                                          "; the mesh has " + std::to_string(V.rows()));
  return *precomputed;
}

} // namespace iarap::detail
