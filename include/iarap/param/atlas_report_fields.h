// The report of uv_atlas as named fields: one list, so that the CLI's JSON and the Python dict name the same
// values the same way.
#pragma once
#include "iarap/param/uv_atlas.h"

namespace iarap {

// Calls visit(name, value) for each field of one chart: int or double (squared mesh units for the energy
// and area).
template <typename Visitor> void visit_atlas_chart(const AtlasChart& chart, Visitor&& visit) {
  visit("faces", chart.faces);
  visit("vertices", chart.vertices);
  visit("area", chart.area);
  visit("energy", chart.energy);
  visit("distortion", chart.distortion);
  visit("flipped", chart.flipped);
  visit("iterations", chart.iterations);
  visit("started_from_input", chart.started_from_input);
}

// Calls visit(name, value) for each field of `report` but the charts (visit_atlas_chart): int or double;
// lengths in mesh units, times in milliseconds.
template <typename Visitor> void visit_atlas_report(const AtlasReport& report, Visitor&& visit) {
  visit("seam_length", report.seam_length);
  visit("flipped", report.flipped);
  visit("degenerate_faces", report.degenerate_faces);
  visit("boundary_overlaps", report.boundary_overlaps);
  visit("overlap_ratio", report.overlap_ratio);
  visit("energy", report.energy);
  visit("area", report.area);
  visit("distortion", report.distortion);
  visit("packing_efficiency", report.packing_efficiency);
  visit("merged_small_charts", report.merged_small_charts);
  visit("splits_for_distortion", report.splits_for_distortion);
  visit("splits_for_overlap", report.splits_for_overlap);
  visit("splits_before_solve", report.splits_before_solve);
  visit("segment_ms", report.segment_ms);
  visit("flatten_ms", report.flatten_ms);
  visit("pack_ms", report.pack_ms);
  visit("parameterize_ms", report.total_ms);
}

} // namespace iarap
