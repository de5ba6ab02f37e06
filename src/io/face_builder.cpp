#include "face_builder.h"

#include "iarap/core/errors.h"
#include "text_reader.h"

#include <limits>

namespace iarap::io_detail {

FaceBuilder::FaceBuilder(std::string path, Location kind, int index_base)
    : path_(std::move(path)), kind_(kind), index_base_(index_base) {}

void FaceBuilder::reserve_triangles(std::size_t count) {
  triangles_.reserve(3 * count);
}

void FaceBuilder::fail(std::int64_t where, const std::string& message) const {
  if (kind_ == Location::line) fail_at_line(path_, where, message);
  fail_at_offset(path_, where, message);
}

void FaceBuilder::note_max(std::int64_t index, std::int64_t where, bool strip) {
  if (index > max_index_) {
    max_index_ = index;
    max_where_ = where;
    max_element_ = strip ? strips_ : polygons_;
    max_in_strip_ = strip;
  }
}

void FaceBuilder::add_polygon(const std::vector<std::int64_t>& corners, std::int64_t where) {
  const std::size_t n = corners.size();
  if (n < 3)
    fail(where,
         "face " + std::to_string(polygons_) + " has " + std::to_string(n) + " corners; at least 3 needed");
  for (std::int64_t c : corners) {
    if (c < 0)
      fail(where, "face " + std::to_string(polygons_) + " uses vertex index " +
                      std::to_string(c + index_base_) +
                      (index_base_ == 1 ? " (indices start at 1)" : " (indices start at 0)"));
    note_max(c, where, false);
  }
  // Fan from the first corner: (c0, ci, ci+1) keeps the polygon's orientation.
  for (std::size_t i = 1; i + 1 < n; ++i) {
    triangles_.push_back(
        static_cast<int>(std::min<std::int64_t>(corners[0], std::numeric_limits<int>::max())));
    triangles_.push_back(
        static_cast<int>(std::min<std::int64_t>(corners[i], std::numeric_limits<int>::max())));
    triangles_.push_back(
        static_cast<int>(std::min<std::int64_t>(corners[i + 1], std::numeric_limits<int>::max())));
  }
  if (n > 3) ++polygons_split_;
  ++polygons_;
}

void FaceBuilder::add_strip(const std::vector<std::int64_t>& strip, std::int64_t where) {
  std::int64_t run = 0; // position in the current run since the last restart
  for (std::size_t i = 0; i < strip.size(); ++i) {
    const std::int64_t c = strip[i];
    if (c == -1) {
      run = 0;
      continue;
    }
    if (c < 0)
      fail(where, "triangle strip " + std::to_string(strips_) + " uses vertex index " + std::to_string(c) +
                      " (only -1, the restart marker, may be negative)");
    note_max(c, where, true);
    if (run == 0) ++strip_runs_;
    ++run;
    if (run < 3) continue;
    const std::int64_t a = strip[i - 2], b = strip[i - 1];
    const std::int64_t k = run - 3; // triangle number within the run
    if (a == b || b == c || a == c) {
      ++strip_degenerate_;
      continue;
    }
    const auto clamp = [](std::int64_t x) {
      return static_cast<int>(std::min<std::int64_t>(x, std::numeric_limits<int>::max()));
    };
    if (k % 2 == 0) {
      triangles_.insert(triangles_.end(), {clamp(a), clamp(b), clamp(c)});
    } else {
      triangles_.insert(triangles_.end(), {clamp(b), clamp(a), clamp(c)});
    }
    ++strip_triangles_;
  }
  ++strips_;
}

Eigen::MatrixXi FaceBuilder::finish(std::int64_t num_vertices, std::vector<std::string>& notes) const {
  if (max_index_ >= num_vertices) {
    fail(max_where_, std::string(max_in_strip_ ? "triangle strip " : "face ") + std::to_string(max_element_) +
                         " uses vertex index " + std::to_string(max_index_ + index_base_) +
                         " but the file has " + std::to_string(num_vertices) + " vertices" +
                         (index_base_ == 1 ? " (indices start at 1)" : " (indices start at 0)"));
  }
  const Eigen::Index nt = static_cast<Eigen::Index>(triangles_.size() / 3);
  Eigen::MatrixXi F(nt, 3);
  for (Eigen::Index t = 0; t < nt; ++t)
    for (int k = 0; k < 3; ++k) F(t, k) = triangles_[static_cast<std::size_t>(3 * t + k)];
  if (polygons_split_ > 0)
    notes.push_back("triangulated " + std::to_string(polygons_split_) +
                    " polygons with more than 3 corners as fans from their first corner; " +
                    std::to_string(polygons_) + " faces became " + std::to_string(nt - strip_triangles_) +
                    " triangles");
  if (strips_ > 0)
    notes.push_back("unrolled " + std::to_string(strips_) + " triangle strip records (" +
                    std::to_string(strip_runs_) + " runs between -1 restarts) into " +
                    std::to_string(strip_triangles_) + " triangles, skipping " +
                    std::to_string(strip_degenerate_) + " degenerate strip triangles with a repeated vertex");
  return F;
}

} // namespace iarap::io_detail
