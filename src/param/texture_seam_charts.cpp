#include "iarap/param/texture_seam_charts.h"

#include "iarap/core/errors.h"

#include "../mesh/disjoint_sets.h"

#include <cstdint>
#include <string>
#include <unordered_map>

namespace iarap {

namespace {

std::uint64_t edge_key(int from, int to) {
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(from)) << 32) |
         static_cast<std::uint32_t>(to);
}

} // namespace

std::vector<int> texture_seam_charts(const Eigen::MatrixXi& F, const Eigen::MatrixXi& FT) {
  if (FT.rows() != F.rows() || FT.cols() != 3 || F.cols() != 3)
    throw InputError("texture indices must be #F x 3 = " + std::to_string(F.rows()) + " x 3; got " +
                     std::to_string(FT.rows()) + " x " + std::to_string(FT.cols()));
  for (Eigen::Index f = 0; f < F.rows(); ++f)
    if ((FT.row(f).array() < 0).any())
      throw InputError("triangle " + std::to_string(f) + " (vertices " + std::to_string(F(f, 0) + 1) + " " +
                       std::to_string(F(f, 1) + 1) + " " + std::to_string(F(f, 2) + 1) +
                       " as the file numbers them) has no texture indices: every face needs i/t corners");
  // Each half-edge (from, to) with the texture indices at its ends; the opposite half-edge (to, from) of
  // the neighbouring face glues when its indices at to and from are the same.
  struct HalfEdge {
    int face, from_texture, to_texture;
  };
  std::unordered_map<std::uint64_t, HalfEdge> half_edges;
  half_edges.reserve(static_cast<std::size_t>(3 * F.rows()));
  for (Eigen::Index f = 0; f < F.rows(); ++f)
    for (int k = 0; k < 3; ++k)
      half_edges.emplace(edge_key(F(f, k), F(f, (k + 1) % 3)),
                         HalfEdge{static_cast<int>(f), FT(f, k), FT(f, (k + 1) % 3)});
  detail::DisjointSets sets(static_cast<int>(F.rows()));
  for (Eigen::Index f = 0; f < F.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      const auto twin = half_edges.find(edge_key(F(f, (k + 1) % 3), F(f, k)));
      if (twin == half_edges.end()) continue;
      const HalfEdge& other = twin->second;
      if (other.from_texture == FT(f, (k + 1) % 3) && other.to_texture == FT(f, k))
        sets.join(static_cast<int>(f), other.face);
    }
  const auto faces = static_cast<std::size_t>(F.rows());
  std::vector<int> chart(faces, -1), id_of_root(faces, -1);
  int charts = 0;
  for (std::size_t f = 0; f < faces; ++f) {
    int& id = id_of_root[static_cast<std::size_t>(sets.find(static_cast<int>(f)))];
    if (id < 0) id = charts++;
    chart[f] = id;
  }
  return chart;
}

} // namespace iarap
