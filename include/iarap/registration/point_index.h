// A k-d tree over a fixed set of 3D points, for the closest-point queries of registration (nanoflann,
// behind a pimpl so that public headers do not include it). The tree is built once in the constructor;
// queries are const and may run from several threads at once.
#pragma once
#include <Eigen/Core>

#include <memory>
#include <vector>

namespace iarap {

class PointIndex {
public:
  PointIndex();
  // points: #P x 3, copied (the index owns them). Throws InputError for a wrong shape.
  explicit PointIndex(const Eigen::MatrixXd& points);
  ~PointIndex();
  PointIndex(PointIndex&&) noexcept;
  PointIndex& operator=(PointIndex&&) noexcept;

  Eigen::Index size() const;

  // The index of the point nearest to q and its squared distance; (-1, inf) for an empty index.
  std::pair<Eigen::Index, double> nearest(const Eigen::Vector3d& q) const;

  // The min(k, size()) points nearest to q, nearest first: indices and squared distances (resized).
  void nearest_k(const Eigen::Vector3d& q, int k, std::vector<Eigen::Index>& indices,
                 std::vector<double>& squared_distances) const;

private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

} // namespace iarap
