#include "iarap/mesh/validate.h"

#include <string>

namespace iarap {

// Each need follows what the precompute refuses: original ARAP and spokes-and-rims take their cotangents
// from the input's faces (a degenerate face: TopologyError naming it), iARAP mollifies degenerate faces'
// lengths and runs as is. Coincident vertices (seams) stop no method: check_mesh's warning suggests the
// repair, but it is not a need.
std::vector<DeformNeed> deform_needs(const MeshReport& report) {
  std::vector<DeformNeed> needs;
  if (!report.deformable()) return needs;
  if (report.zero_area_faces > 0)
    needs.push_back({"--repair",
                     std::to_string(report.zero_area_faces) +
                         " zero-area faces (infinite cotangent weights), which it drops; iarap runs as is "
                         "(it mollifies their lengths)",
                     {"arap", "spokes-rims"}});
  if (report.components > 1)
    needs.push_back(
        {"--pin-unconstrained",
         std::to_string(report.components) +
             " components: each needs a constraint, or this flag pins one vertex of each that has "
             "none",
         {"arap", "spokes-rims", "iarap"}});
  return needs;
}

} // namespace iarap
