// Overlap checks of UV maps (uv_atlas.h).
#pragma once
#include <Eigen/Core>
#include <vector>

namespace iarap::param_detail {

// Whether the closed polygon UV(loop[0]), UV(loop[1]), ... crosses or touches itself: every pair of its
// segments that share no end is tested for intersection (orientation tests, touching counts), pairs found
// through a uniform grid of about one cell per segment over the loop's bounding box. A flip-free map of a
// disk whose boundary is a simple closed curve is one to one (the boundary's image bounds its interior's),
// so together with no flipped triangle this certifies a chart overlaps nowhere.
bool loop_crosses_itself(const Eigen::MatrixXd& UV, const std::vector<int>& loop);

// The share of covered texels that two triangles cover: the faces' corners corner_uv (rows 3 f + k, in
// [0,1]^2), faces with use[f] = false skipped, rasterized at resolution x resolution texel centres, a
// centre counted in a triangle when strictly inside it (so that triangles sharing an edge count once).
// Returns texels covered twice or more / texels covered (0 when none is covered).
double rasterized_overlap(const Eigen::MatrixXd& corner_uv, const std::vector<bool>& use, int resolution);

} // namespace iarap::param_detail
