#include "iarap/param/disk_mesh.h"

#include "iarap/core/errors.h"
#include "iarap/mesh/validate.h"
#include "iarap/param/boundary_loops.h"

#include <cmath>
#include <string>

namespace iarap {

namespace {

// The zero-area threshold of check_mesh, relative to the bounding-box diagonal squared.
constexpr double zero_area_factor = 1e-12;

std::string plural(int n, const std::string& one, const std::string& many) {
  return std::to_string(n) + " " + (n == 1 ? one : many);
}

} // namespace

void check_param_arrays(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F) {
  if (V.cols() != 3)
    throw InputError("V must be #V x 3 (x y z per vertex); got " + std::to_string(V.rows()) + " x " +
                     std::to_string(V.cols()));
  if (F.cols() != 3)
    throw InputError("F must be #F x 3 (three vertex indices per triangle); got " + std::to_string(F.rows()) +
                     " x " + std::to_string(F.cols()));
  if (F.rows() == 0) throw InputError("the mesh has no faces");
  for (Eigen::Index v = 0; v < V.rows(); ++v)
    if (!V.row(v).allFinite())
      throw InputError("vertex " + std::to_string(v) + " has a non-finite coordinate (" +
                       std::to_string(V(v, 0)) + ", " + std::to_string(V(v, 1)) + ", " +
                       std::to_string(V(v, 2)) + ")");
  for (Eigen::Index f = 0; f < F.rows(); ++f)
    for (int k = 0; k < 3; ++k)
      if (F(f, k) < 0 || F(f, k) >= V.rows())
        throw InputError("face " + std::to_string(f) + " uses vertex " + std::to_string(F(f, k)) +
                         "; the mesh has " + std::to_string(V.rows()) + " vertices");
}

namespace {

// Every vertex in a face and every face with an area: a parameterization has a Jacobian per face and a
// row per vertex in its systems.
void check_elements(const DiskMesh& disk, double bbox_diagonal) {
  std::vector<char> used(static_cast<std::size_t>(disk.V.rows()), 0);
  for (Eigen::Index f = 0; f < disk.F.rows(); ++f)
    for (int k = 0; k < 3; ++k) used[static_cast<std::size_t>(disk.F(f, k))] = 1;
  for (std::size_t v = 0; v < used.size(); ++v)
    if (!used[v])
      throw TopologyError("vertex " + std::to_string(v) +
                          " is used by no face and would have no place in the map; remove unreferenced "
                          "vertices first (repair_mesh)");
  const double min_area = zero_area_factor * bbox_diagonal * bbox_diagonal;
  for (Eigen::Index f = 0; f < disk.F.rows(); ++f)
    if (!(disk.frames.area(f) > min_area))
      throw TopologyError("face " + std::to_string(f) + " (vertices " + std::to_string(disk.F(f, 0)) + ", " +
                          std::to_string(disk.F(f, 1)) + ", " + std::to_string(disk.F(f, 2)) + ") has area " +
                          std::to_string(disk.frames.area(f)) +
                          " (<= 1e-12 x bbox diagonal^2): a degenerate triangle has no Jacobian; remove it "
                          "first (repair_mesh with remove_zero_area)");
}

std::string topology_text(const MeshReport& check) {
  std::string text = plural(check.components, "component", "components") + ", " +
                     plural(check.boundary_loops, "boundary loop", "boundary loops");
  if (check.genus) text += " and genus " + std::to_string(*check.genus);
  return text;
}

void check_disk_topology(const MeshReport& check) {
  if (!check.usable()) {
    std::string message = "mesh not usable for parameterization:";
    for (const auto& error : check.errors) message += "\n  " + error;
    throw TopologyError(message);
  }
  const std::string what =
      "the mesh is not a topological disk (one component, one boundary loop, genus 0): it "
      "has " +
      topology_text(check);
  if (check.components != 1)
    throw TopologyError(what +
                        "; parameterize each component on its own (vertex_components) after cutting it "
                        "into disks");
  if (check.boundary_loops == 0)
    throw TopologyError(what +
                        "; a closed surface cannot be flattened into one chart: cut it into disks first");
  if (check.boundary_loops > 1 || check.genus.value_or(0) != 0)
    throw TopologyError(what +
                        "; cut it into disks first (along paths joining the boundary loops, and through "
                        "each handle)");
}

} // namespace

DiskMesh prepare_disk(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F) {
  check_param_arrays(V, F);
  const MeshReport check = check_mesh(V, F);
  check_disk_topology(check);
  DiskMesh disk;
  disk.V = V;
  disk.F = F;
  disk.frames = triangle_frames(V, F);
  check_elements(disk, check.bbox_diagonal);
  std::vector<std::vector<int>> loops = boundary_loops(F, static_cast<int>(V.rows()));
  disk.boundary = std::move(loops.front()); // check_disk_topology: exactly one
  disk.area = disk.frames.area.sum();
  return disk;
}

DiskMesh prepare_chart_disk(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F) {
  std::vector<std::vector<int>> loops = boundary_loops(F, static_cast<int>(V.rows()));
  // Euler characteristic V - E + F with 2 E = 3 F + (boundary edges): 1 for a disk.
  std::size_t boundary_edges = 0;
  for (const std::vector<int>& loop : loops) boundary_edges += loop.size();
  const auto edges = (3 * static_cast<std::size_t>(F.rows()) + boundary_edges) / 2;
  const auto euler = static_cast<std::int64_t>(V.rows()) - static_cast<std::int64_t>(edges) + F.rows();
  if (loops.size() != 1 || euler != 1)
    throw TopologyError("the chart is not a topological disk: " +
                        plural(static_cast<int>(loops.size()), "boundary loop", "boundary loops") +
                        ", Euler characteristic " + std::to_string(euler));
  DiskMesh disk;
  disk.V = V;
  disk.F = F;
  disk.frames = triangle_frames(V, F);
  disk.boundary = std::move(loops.front());
  disk.area = disk.frames.area.sum();
  return disk;
}

} // namespace iarap
