// Mesh files, validation and repair: read_mesh, write_mesh, check_mesh, repair_mesh.
#include "bindings.h"
#include "numpy_arrays.h"

#include "iarap/io/read_mesh.h"
#include "iarap/io/read_tet_mesh.h"
#include "iarap/io/write_mesh.h"
#include "iarap/io/write_tet_mesh.h"
#include "iarap/mesh/repair.h"
#include "iarap/mesh/validate.h"

namespace iarap::python {
namespace {

py::tuple read_mesh_py(const py::object& path) {
  const std::string file = to_path(path);
  MeshData mesh;
  {
    py::gil_scoped_release release;
    mesh = read_mesh(file);
  }
  return py::make_tuple(to_numpy(mesh.V), to_numpy(mesh.F));
}

void write_mesh_py(const py::object& path, const py::object& V, const py::object& F) {
  const std::string file = to_path(path);
  const Eigen::MatrixXd positions = to_points(V, "V");
  const Eigen::MatrixXi faces = to_faces(F, "F", positions.rows());
  py::gil_scoped_release release;
  write_mesh(file, positions, faces);
}

py::tuple read_tet_mesh_py(const py::object& path) {
  const std::string file = to_path(path);
  TetMesh mesh;
  {
    py::gil_scoped_release release;
    mesh = read_tet_mesh(file);
  }
  return py::make_tuple(to_numpy(mesh.V), to_numpy(mesh.T));
}

void write_tet_mesh_py(const py::object& path, const py::object& V, const py::object& T) {
  const std::string file = to_path(path);
  const Eigen::MatrixXd positions = to_points(V, "V");
  const Eigen::MatrixXi tets = to_faces(T, "T", positions.rows(), 4);
  py::gil_scoped_release release;
  write_tet_mesh(file, positions, tets);
}

py::dict report_to_dict(const MeshReport& report) {
  py::dict d;
  d["usable"] = report.usable();
  d["vertices"] = report.vertices;
  d["faces"] = report.faces;
  d["components"] = report.components;
  d["boundary_loops"] = report.boundary_loops;
  d["genus"] = report.genus ? py::object(py::int_(*report.genus)) : py::object(py::none());
  d["non_manifold_edges"] = report.non_manifold_edges;
  d["non_manifold_vertices"] = report.non_manifold_vertices;
  d["zero_area_faces"] = report.zero_area_faces;
  d["unreferenced_vertices"] = report.unreferenced_vertices;
  d["non_delaunay_edges"] = report.non_delaunay_edges;
  d["inconsistently_oriented_edges"] = report.inconsistently_oriented_edges;
  d["repeated_vertex_faces"] = report.repeated_vertex_faces;
  d["out_of_range_indices"] = report.out_of_range_indices;
  d["non_finite_coordinates"] = report.non_finite_coordinates;
  d["coincident_vertices"] = report.coincident_vertices;
  d["boundary_edges"] = report.boundary_edges;
  d["bbox_diagonal"] = report.bbox_diagonal;
  d["errors"] = report.errors;
  d["warnings"] = report.warnings;
  return d;
}

py::dict check_mesh_py(const py::object& V, const py::object& F) {
  // The validator reports NaN coordinates, bad indices and wrong column counts itself; only what cannot
  // be represented (not 2-D, not numeric, indices beyond int) is a ValueError here.
  const Eigen::MatrixXd positions = to_points(V, "V", /*require_finite=*/false);
  const Eigen::MatrixXi faces = to_faces(F, "F", /*vertex_count=*/-1, /*columns=*/-1);
  MeshReport report;
  {
    py::gil_scoped_release release;
    report = check_mesh(positions, faces);
  }
  return report_to_dict(report);
}

// repair_mesh as `iarap repair` and `deform --repair` run it (zero-area faces removed).
py::tuple repair_mesh_py(const py::object& V, const py::object& F, double weld_tolerance,
                         bool split_open_fans) {
  const Eigen::MatrixXd positions = to_points(V, "V");
  const Eigen::MatrixXi faces = to_faces(F, "F", positions.rows());
  RepairOptions options;
  options.remove_zero_area = true;
  options.weld_tolerance = weld_tolerance;
  options.split_open_fans = split_open_fans;
  RepairResult repaired;
  {
    py::gil_scoped_release release;
    repaired = repair_mesh(positions, faces, options);
  }
  py::dict report;
  report["actions"] = repaired.actions;
  visit_repair_counts(repaired.counts, [&report](const char* name, int value) { report[name] = value; });
  report["old_to_new"] = to_numpy(repaired.old_to_new);
  return py::make_tuple(to_numpy(repaired.V), to_numpy(repaired.F), to_numpy(repaired.new_to_old), report);
}

} // namespace

void bind_io(py::module_& m) {
  m.def("read_mesh", &read_mesh_py, py::arg("path"),
        R"(Reads a triangle mesh from an .obj, .off, .ply (ASCII or binary) or .stl file.

Returns (V, F): V float64 (#V, 3) positions in the file's units and vertex order, F int64 (#F, 3) 0-based
vertex indices (polygons fan-triangulated). STL vertices are welded by identical position.
Raises InputError (a ValueError) naming path:line for unreadable or malformed files.)");
  m.def("write_mesh", &write_mesh_py, py::arg("path"), py::arg("V"), py::arg("F"),
        R"(Writes V (#V, 3) and F (#F, 3) to an .obj, .off or .ply (ASCII) file, atomically, coordinates
printed with 17 significant digits (a read gives back the same doubles).
Raises ValueError for bad arrays or an unsupported extension or an unwritable path.)");
  m.def(
      "read_tet_mesh", &read_tet_mesh_py, py::arg("path"),
      R"(Reads a tetrahedral mesh from a MEDIT .mesh, TetGen .node / .ele or gmsh .msh (2.2, 4.1 ASCII) file.

Returns (V, T): V float64 (#V, 3) positions in the file's order, T int64 (#T, 4) 0-based vertex indices,
every tetrahedron of positive volume (a file whose tetrahedra are all negative is reoriented). Raises
InputError (a ValueError) naming path:line for malformed files, indices out of range, a repeated vertex, a
tetrahedron of zero volume or mixed orientations.)");
  m.def("write_tet_mesh", &write_tet_mesh_py, py::arg("path"), py::arg("V"), py::arg("T"),
        R"(Writes V (#V, 3) and T (#T, 4) to a MEDIT .mesh file, atomically, coordinates with 17 significant
digits. Raises ValueError for bad arrays, another extension or an unwritable path.)");
  m.def(
      "tet_boundary_faces",
      [](const py::object& T) { return to_numpy(tet_boundary_faces(to_faces(T, "T", -1, 4))); }, py::arg("T"),
      R"(The boundary faces (#B, 3) of tetrahedra T (#T, 4): the faces used by one tetrahedron, outward for
positive tetrahedra, in the order of their tetrahedra. What ARAP(V, T, ...) indexes with soft_faces.)");
  m.def("check_mesh", &check_mesh_py, py::arg("V"), py::arg("F"),
        R"(Validation report of a triangle mesh before ARAP, as a dict.

V (#V, 3) positions (NaN / Inf allowed: they are reported), F (#F, k) integer vertex indices (out-of-range
entries and k != 3 are reported). Keys: usable (bool: no errors), vertices, faces, components,
boundary_loops, genus (None when non-manifold or non-orientable), non_manifold_edges,
non_manifold_vertices, zero_area_faces, unreferenced_vertices, non_delaunay_edges,
inconsistently_oriented_edges, repeated_vertex_faces, out_of_range_indices, non_finite_coordinates,
coincident_vertices, boundary_edges, bbox_diagonal (mesh units), errors and warnings (lists of messages
naming the first offending element).)");
  m.def("repair_mesh", &repair_mesh_py, py::arg("V"), py::arg("F"), py::kw_only(),
        py::arg("weld_tolerance") = 1e-12, py::arg("split_open_fans") = false,
        R"(Repairs a triangle mesh as `iarap repair` and `deform --repair` do: weld vertices closer than
weld_tolerance x the bounding-box diagonal, drop faces that collapse, repeat a vertex, have zero area or repeat
another face, separate non-manifold edges into sheets and split non-manifold vertices (split_open_fans: also
where only open fans touch), orient every orientable piece consistently, drop unreferenced vertices.

Returns (V, F, new_to_old, report): the repaired float64 (#V', 3) and int64 (#F', 3) arrays (vertices that
stay in input order, then the copies of split ones, each at its vertex's position), new_to_old (#V',) the
input vertex each output vertex stands for (copies share one), and a dict: actions (one line per kind of
change), the counts (welded_vertices, collapsed_faces, repeated_vertex_faces, zero_area_faces,
duplicate_faces, split_edges, split_vertices, vertex_copies, flipped_faces, non_orientable_pieces,
unreferenced_vertices) and old_to_new (#V,) the output index of each input vertex (its first copy), -1 where
removed. A non-orientable piece (Moebius strip) is left as it is: check_mesh names it.
Raises ValueError for bad arrays (indices out of range, non-finite coordinates).)");
}

} // namespace iarap::python
