// nanoflann's k-d tree over an owned row-major copy of the points. nanoflann rather than a hand-written
// tree: header-only, packaged by Debian (libnanoflann-dev), exact queries, thread-safe searches.
#include "iarap/registration/point_index.h"

#include "iarap/core/errors.h"

#include <nanoflann.hpp>

#include <cstdint>
#include <limits>

namespace iarap {

namespace {

struct Cloud {
  Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor> P;
  std::size_t kdtree_get_point_count() const { return static_cast<std::size_t>(P.rows()); }
  double kdtree_get_pt(std::size_t i, std::size_t d) const {
    return P(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(d));
  }
  template <class Box> bool kdtree_get_bbox(Box&) const { return false; }
};

using Tree =
    nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<double, Cloud>, Cloud, 3, std::uint32_t>;

} // namespace

struct PointIndex::Impl {
  Cloud cloud;
  std::unique_ptr<Tree> tree; // refers to cloud: Impl stays where it was allocated
};

PointIndex::PointIndex() = default;
PointIndex::~PointIndex() = default;
PointIndex::PointIndex(PointIndex&&) noexcept = default;
PointIndex& PointIndex::operator=(PointIndex&&) noexcept = default;

PointIndex::PointIndex(const Eigen::MatrixXd& points) : impl_(std::make_unique<Impl>()) {
  if (points.cols() != 3) {
    throw InputError("PointIndex: points must be #P x 3; got " + std::to_string(points.rows()) + " x " +
                     std::to_string(points.cols()));
  }
  if (points.rows() > std::numeric_limits<std::uint32_t>::max())
    throw InputError("PointIndex: more than 2^32 - 1 points");
  impl_->cloud.P = points;
  impl_->tree = std::make_unique<Tree>(3, impl_->cloud, nanoflann::KDTreeSingleIndexAdaptorParams(10));
}

Eigen::Index PointIndex::size() const {
  return impl_ ? impl_->cloud.P.rows() : 0;
}

std::pair<Eigen::Index, double> PointIndex::nearest(const Eigen::Vector3d& q) const {
  if (size() == 0) return {-1, std::numeric_limits<double>::infinity()};
  std::uint32_t index = 0;
  double squared = 0;
  impl_->tree->knnSearch(q.data(), 1, &index, &squared);
  return {static_cast<Eigen::Index>(index), squared};
}

void PointIndex::nearest_k(const Eigen::Vector3d& q, int k, std::vector<Eigen::Index>& indices,
                           std::vector<double>& squared_distances) const {
  const auto n = static_cast<std::size_t>(std::max<Eigen::Index>(0, std::min<Eigen::Index>(k, size())));
  std::vector<std::uint32_t> found(n);
  squared_distances.resize(n);
  const std::size_t got =
      n == 0 ? 0 : impl_->tree->knnSearch(q.data(), n, found.data(), squared_distances.data());
  indices.resize(got);
  squared_distances.resize(got);
  for (std::size_t i = 0; i < got; ++i) indices[i] = static_cast<Eigen::Index>(found[i]);
}

} // namespace iarap
