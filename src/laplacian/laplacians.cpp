#include "iarap/laplacian/laplacians.h"

#include "iarap/core/errors.h"
#include "iarap/laplacian/first_segment_laplacians.h"
#include "iarap/laplacian/iarap_laplacian.h"
#include "iarap/laplacian/intrinsic_cotan_laplacian.h"
#include "iarap/mesh/cotan.h"
#include "intrinsic_for_mesh.h"

#include <optional>

namespace iarap {

const std::vector<LaplacianKind>& all_laplacian_kinds() {
  static const std::vector<LaplacianKind> kinds{LaplacianKind::Cotan,    LaplacianKind::Intrinsic,
                                                LaplacianKind::Iarap,    LaplacianKind::IarapPlus,
                                                LaplacianKind::IarapSym, LaplacianKind::IarapRefined};
  return kinds;
}

std::string laplacian_kind_name(LaplacianKind kind) {
  switch (kind) {
  case LaplacianKind::Cotan:
    return "cotan";
  case LaplacianKind::Intrinsic:
    return "intrinsic";
  case LaplacianKind::Iarap:
    return "iarap";
  case LaplacianKind::IarapPlus:
    return "iarap-plus";
  case LaplacianKind::IarapSym:
    return "iarap-sym";
  case LaplacianKind::IarapRefined:
    return "iarap-refined";
  }
  throw InputError("unknown Laplacian kind " + std::to_string(static_cast<int>(kind)));
}

LaplacianKind parse_laplacian_kind(const std::string& name) {
  for (LaplacianKind kind : all_laplacian_kinds())
    if (laplacian_kind_name(kind) == name) return kind;
  throw InputError("unknown Laplacian kind '" + name +
                   "'; expected cotan, intrinsic, iarap, iarap-plus, iarap-sym or iarap-refined");
}

Eigen::SparseMatrix<double> laplacian(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, LaplacianKind kind,
                                      const IntrinsicDelaunay* precomputed) {
  if (kind == LaplacianKind::Cotan) return cotan_laplacian(V, F);
  if (kind == LaplacianKind::IarapRefined) {
    // Its own triangulation: the refined one has inserted boundary points a precomputed plain one lacks.
    IntrinsicOptions options;
    options.refine_boundary = true;
    options.keep_traces = false;
    return iarap_laplacian(intrinsic_delaunay(V, F, options).segments, static_cast<int>(V.rows()));
  }
  std::optional<IntrinsicDelaunay> storage;
  const IntrinsicDelaunay& idt = detail::intrinsic_for_mesh(V, F, precomputed, storage);
  const int num_vertices = static_cast<int>(V.rows());
  switch (kind) {
  case LaplacianKind::Intrinsic:
    return intrinsic_cotan_laplacian(idt.triangulation, num_vertices);
  case LaplacianKind::Iarap:
    return iarap_laplacian(idt.segments, num_vertices);
  case LaplacianKind::IarapPlus:
    return iarap_plus_laplacian(V, idt);
  case LaplacianKind::IarapSym:
    return iarap_sym_laplacian(V, idt);
  case LaplacianKind::Cotan:
  case LaplacianKind::IarapRefined:
    break;
  }
  return cotan_laplacian(V, F);
}

} // namespace iarap
