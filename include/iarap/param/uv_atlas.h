// A UV atlas of any triangle mesh (issue 49): charts that are topological disks, each flattened flip-free by
// arap_parameterize, split where their ARAP distortion is high or their boundary overlaps itself, and
// packed into the unit square with a padding in texels.
//
// Method (src/param/chart_segmentation.h): charts grown over the faces from seeds by a priority queue on
// the deviation of a face's normal from the chart's mean normal, within a normal cone, in the manner of
// Sander, Snyder, Gortler and Hoppe 2001 ("Texture mapping progressive meshes", greedy face clustering) and
// Levy, Petitjean, Ray and Maillot 2002 (LSCM's charts grown from seeds up to a feature boundary). A face
// joins a chart only if the chart stays a topological disk: it shares exactly one edge with the chart and
// its third vertex is new to the chart, or two edges (it fills a notch). So every chart is a disk whatever
// the genus, boundary loops or components, without computing a cut graph first; seams fall where the
// normal turns fastest (sharp features). Charts below the minimum size are dissolved into their neighbours.
// Then, the distortion-driven splitting of the Blender / xatlas family: a flattened chart whose energy per
// area exceeds the target, or whose UV boundary crosses itself, is regrown from its two farthest faces
// into two charts and flattened again. A chart whose LSCM start (the ARAP solve's start) already crosses
// itself is split before the solve. Charts are flattened in parallel (OpenMP, thread_count() threads),
// each on one thread, so the atlas does not depend on the thread count.
#pragma once
#include "iarap/param/param_options.h"

#include <Eigen/Core>
#include <vector>

namespace iarap {

// How an atlas flattens its charts by default: ParamOptions' defaults but the engine's tolerance 1e-4
// (iterations stop when one lowers the energy by at most 1e-4 of itself). Measured (docs/param.md): the
// beetle's atlas took 2.15 s against 5.0 s with 1e-6, the ogre's 6.7 s against 11.2 s, the charts'
// energies changing in the 5th digit, far below any distortion target.
ParamOptions default_atlas_param_options();

struct AtlasOptions {
  ParamOptions param = default_atlas_param_options(); // each chart's flattening (energy, flips, engine)
  double max_normal_angle = 60;    // degrees: a face joins a chart within this angle of its mean normal
  double target_distortion = 0.05; // split a chart whose energy / area exceeds this (squared strain)
  int min_chart_faces = 16;        // smaller charts are merged into neighbours; no split makes smaller ones
  int texture_size = 1024;         // texels along a side of the unit square
  double padding = 2;              // texels between charts (half of it to the square's border)
  int max_rounds = 8;              // rounds of splitting flattened charts
};

// What a caller may give beside the mesh (each part optional, empty when not given).
struct AtlasInput {
  // #F polygon ids (a face with an id < 0 is a polygon of its own), e.g. read_obj_textured's
  // polygon_of_triangle: the faces of one polygon join one chart together, so that the polygon, written
  // back, has one UV per corner.
  std::vector<int> polygon_of_face;
  // #F chart ids >= 0 (`--charts keep`: texture_seam_charts of an OBJ's vt): the charts to flatten instead
  // of segmenting the mesh. They are not split for distortion; one whose flattening crosses itself is split
  // as the atlas splits its own; one that is not a disk is refused (TopologyError naming the chart).
  std::vector<int> charts;
  // (3 #F) x 2 corner UVs with `charts` (the file's vt): each chart starts from them, scaled to its surface
  // area, when they fold none of its triangles (else from the default start).
  Eigen::MatrixXd corner_uv;
};

struct AtlasChart {
  int faces = 0, vertices = 0;
  double area = 0;            // surface area
  double energy = 0;          // per-triangle ARAP energy of its flattening (squared mesh units)
  double distortion = 0;      // energy / area
  int flipped = 0;            // triangles with det J <= 0 in its flattening
  int iterations = 0;         // of the engine
  int started_from_input = 0; // 1: its flattening started from AtlasInput::corner_uv
};

struct AtlasReport {
  std::vector<AtlasChart> charts;
  int splits_for_distortion = 0, splits_for_overlap = 0, merged_small_charts = 0;
  // Of splits_for_overlap, those made because the chart's LSCM start already crossed itself: split before
  // the ARAP solve, which its parts need instead.
  int splits_before_solve = 0;
  double seam_length = 0;    // mesh units: edges whose two faces lie in different charts
  int flipped = 0;           // triangles with a UV area <= 0 in the atlas (degenerate input faces excluded)
  int degenerate_faces = 0;  // input faces without an area, their corners put on one UV point
  int boundary_overlaps = 0; // charts left with a self-crossing UV boundary (after max_rounds)
  double energy = 0, area = 0, distortion = 0; // sums over the charts, energy / area
  double packing_efficiency = 0;               // UV area of the charts / the unit square
  double overlap_ratio = 0; // texels covered by two triangles / texels covered (texture_size^2 raster)
  double segment_ms = 0, flatten_ms = 0, pack_ms = 0, total_ms = 0;
};

struct UvAtlas {
  Eigen::MatrixXd corner_uv; // (3 #F) x 2: row 3 f + k the UV of corner k of face f, inside [0,1]^2
  Eigen::VectorXi chart;     // #F chart of each face (-1 for a degenerate face)
  AtlasReport report;
};

// The atlas of (V #V x 3, F #F x 3). Throws InputError for bad arrays or options (naming the element or
// option) and TopologyError for a mesh that is not an oriented manifold (what check_mesh reports: edges with
// three faces, vertices joining separate fans, inconsistent orientation), which cannot be cut into disks
// without a repair. Faces without an area are left out of the charts (counted in degenerate_faces).
UvAtlas uv_atlas(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, const AtlasOptions& options = {});

// The same with polygons, given charts or a given layout (AtlasInput); InputError for parts of the wrong
// size or a negative chart id.
UvAtlas uv_atlas(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, const AtlasOptions& options,
                 const AtlasInput& input);

} // namespace iarap
