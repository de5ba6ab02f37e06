// Internal: collects the faces of a mesh file as triangles (polygons fan-triangulated from their first
// corner, triangle strips unrolled), checks vertex indices and writes the notes the readers return.
#pragma once
#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

namespace iarap::io_detail {

enum class Location { line, byte_offset };

class FaceBuilder {
public:
  // index_base: how the file numbers vertices (1 for OBJ), used only to print indices as written.
  FaceBuilder(std::string path, Location kind, int index_base = 0);

  // Capacity hint; callers cap it by what the remaining bytes could hold.
  void reserve_triangles(std::size_t count);

  // One polygon of corners.size() >= 3 vertices (0-based). `where` is the line or byte offset for errors.
  // Throws InputError for fewer than 3 corners or a negative index.
  void add_polygon(const std::vector<std::int64_t>& corners, std::int64_t where);

  // One triangle strip; -1 restarts the strip. Triangle k of a run (a, b, c) is kept as is for even k and
  // as (b, a, c) for odd k so that all share the orientation; triangles with a repeated vertex are skipped.
  void add_strip(const std::vector<std::int64_t>& strip, std::int64_t where);

  // #F x 3 triangles after checking every index against num_vertices (throws InputError naming the face or
  // strip with the largest index and its location); appends what was triangulated to notes.
  Eigen::MatrixXi finish(std::int64_t num_vertices, std::vector<std::string>& notes) const;

private:
  [[noreturn]] void fail(std::int64_t where, const std::string& message) const;
  void note_max(std::int64_t index, std::int64_t where, bool strip);

  std::string path_;
  Location kind_;
  int index_base_;
  std::vector<int> triangles_; // flat, 3 per triangle
  std::int64_t polygons_ = 0, polygons_split_ = 0, strips_ = 0, strip_runs_ = 0, strip_degenerate_ = 0,
               strip_triangles_ = 0;
  // The largest index seen and where, so one check at the end names the worst offender.
  std::int64_t max_index_ = -1, max_where_ = 0, max_element_ = 0;
  bool max_in_strip_ = false;
};

} // namespace iarap::io_detail
