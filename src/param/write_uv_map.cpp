#include "iarap/param/write_uv_map.h"

#include "../io/atomic_file.h"
#include "../io/file_extension.h"
#include "../io/writer_support.h"

#include "iarap/core/errors.h"

#include <cstdint>
#include <vector>

namespace iarap {

namespace {

void append_uv_lines(std::string& out, const Eigen::MatrixXd& UV, const char* prefix) {
  for (Eigen::Index v = 0; v < UV.rows(); ++v) {
    out += prefix;
    io_detail::append_double(out, UV(v, 0));
    out += ' ';
    io_detail::append_double(out, UV(v, 1));
    out += '\n';
  }
}

// `f a/ta b/tb c/tc`: vertex indices F and texture coordinate indices T (0-based), written from 1.
void append_textured_faces(std::string& out, const Eigen::MatrixXi& F, const Eigen::MatrixXi& T) {
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    out += 'f';
    for (int k = 0; k < 3; ++k) {
      out += ' ';
      io_detail::append_int(out, F(f, k) + 1LL);
      out += '/';
      io_detail::append_int(out, T(f, k) + 1LL);
    }
    out += '\n';
  }
}

// The extension (.obj or .txt) and the mesh arrays, for either writer; returns the extension.
std::string checked_uv_extension(const std::string& path, const Eigen::MatrixXd& V, const Eigen::MatrixXi& F,
                                 const std::string& what) {
  const std::string extension = io_detail::lower_extension(path);
  if (extension != ".obj" && extension != ".txt")
    throw InputError(path + ": cannot write " + what + " as '" + extension +
                     "'; use .obj (mesh with vt) or .txt (u v)");
  io_detail::check_mesh_arrays(path, V, F);
  return extension;
}

} // namespace

void write_uv_map(const std::string& path, const Eigen::MatrixXd& V, const Eigen::MatrixXi& F,
                  const Eigen::MatrixXd& UV) {
  const std::string extension = checked_uv_extension(path, V, F, "a UV map");
  if (UV.rows() != V.rows() || UV.cols() != 2)
    throw InputError(path + ": UV must be #V x 2 = " + std::to_string(V.rows()) + " x 2; got " +
                     std::to_string(UV.rows()) + " x " + std::to_string(UV.cols()));
  std::string out;
  if (extension == ".txt") {
    out.reserve(static_cast<std::size_t>(UV.rows() * 48));
    append_uv_lines(out, UV, "");
  } else {
    out.reserve(static_cast<std::size_t>(V.rows() * 110 + F.rows() * 48));
    out += "# UV map written by iarap\n";
    io_detail::append_vertex_lines(out, V, "v ");
    append_uv_lines(out, UV, "vt ");
    append_textured_faces(out, F, F); // one vt per vertex
  }
  io_detail::write_file_atomically(path, out);
}

namespace {

// An atlas's faces as polygons: corner c of polygon p is corners first[p] + c, at vertex[.] with uv[.].
struct CornerFaces {
  std::vector<int> first{0}, vertex;
  Eigen::MatrixXd uv; // one row per corner
};

// .txt: one `u v` line per corner; .obj: the `v` lines, one `vt` per distinct (vertex, uv) pair in order
// of first use, and `f a/ta b/tb ...` per polygon.
void write_corner_faces(const std::string& path, const std::string& extension, const Eigen::MatrixXd& V,
                        const CornerFaces& faces) {
  std::string out;
  auto append_uv = [&out](const char* prefix, double u, double v) {
    out += prefix;
    io_detail::append_double(out, u);
    out += ' ';
    io_detail::append_double(out, v);
    out += '\n';
  };
  const Eigen::Index corners = faces.uv.rows();
  if (extension == ".txt") {
    out.reserve(static_cast<std::size_t>(corners * 48));
    for (Eigen::Index c = 0; c < corners; ++c) append_uv("", faces.uv(c, 0), faces.uv(c, 1));
    io_detail::write_file_atomically(path, out);
    return;
  }
  out.reserve(static_cast<std::size_t>(V.rows() * 110 + corners * 45));
  out += "# UV atlas written by iarap\n";
  io_detail::append_vertex_lines(out, V, "v ");
  // (vertex, u, v) -> vt index from 0: per vertex the chain of its distinct UVs (one, or one per chart at
  // a seam), compared with == as a key would be.
  struct TextureCoordinate {
    double u, v;
    int next; // the vertex's next vt, -1 at the end
  };
  std::vector<TextureCoordinate> texture;
  texture.reserve(static_cast<std::size_t>(V.rows()) + static_cast<std::size_t>(corners) / 8);
  std::vector<int> first_texture(static_cast<std::size_t>(V.rows()), -1);
  std::vector<int> corner_vt(static_cast<std::size_t>(corners));
  for (Eigen::Index c = 0; c < corners; ++c) {
    const double u = faces.uv(c, 0), v = faces.uv(c, 1);
    int* link = &first_texture[static_cast<std::size_t>(faces.vertex[static_cast<std::size_t>(c)])];
    while (*link >= 0 && !(texture[static_cast<std::size_t>(*link)].u == u &&
                           texture[static_cast<std::size_t>(*link)].v == v))
      link = &texture[static_cast<std::size_t>(*link)].next;
    int index = *link;
    if (index < 0) {
      index = *link = static_cast<int>(texture.size()); // before push_back, which may move `link`'s target
      texture.push_back({u, v, -1});
      append_uv("vt ", u, v);
    }
    corner_vt[static_cast<std::size_t>(c)] = index;
  }
  for (std::size_t p = 0; p + 1 < faces.first.size(); ++p) {
    out += 'f';
    for (int c = faces.first[p]; c < faces.first[p + 1]; ++c) {
      out += ' ';
      io_detail::append_int(out, faces.vertex[static_cast<std::size_t>(c)] + 1LL);
      out += '/';
      io_detail::append_int(out, corner_vt[static_cast<std::size_t>(c)] + 1LL);
    }
    out += '\n';
  }
  io_detail::write_file_atomically(path, out);
}

void check_corner_uv(const std::string& path, const Eigen::MatrixXi& F, const Eigen::MatrixXd& corner_uv) {
  if (corner_uv.rows() != 3 * F.rows() || corner_uv.cols() != 2)
    throw InputError(path + ": corner UVs must be (3 #F) x 2 = " + std::to_string(3 * F.rows()) +
                     " x 2; got " + std::to_string(corner_uv.rows()) + " x " +
                     std::to_string(corner_uv.cols()));
}

} // namespace

void write_uv_atlas(const std::string& path, const Eigen::MatrixXd& V, const Eigen::MatrixXi& F,
                    const Eigen::MatrixXd& corner_uv) {
  const std::string extension = checked_uv_extension(path, V, F, "a UV atlas");
  check_corner_uv(path, F, corner_uv);
  CornerFaces faces;
  faces.uv = corner_uv;
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    for (int k = 0; k < 3; ++k) faces.vertex.push_back(F(f, k));
    faces.first.push_back(static_cast<int>(faces.vertex.size()));
  }
  write_corner_faces(path, extension, V, faces);
}

void write_uv_atlas_polygons(const std::string& path, const Eigen::MatrixXd& V, const Eigen::MatrixXi& F,
                             const Eigen::MatrixXd& corner_uv, const Eigen::VectorXi& chart,
                             const ObjPolygons& polygons) {
  const std::string extension = checked_uv_extension(path, V, F, "a UV atlas");
  check_corner_uv(path, F, corner_uv);
  std::int64_t triangles = 0;
  for (int p = 0; p < polygons.size(); ++p) triangles += polygons.corners(p) - 2;
  if (triangles != F.rows() || chart.size() != F.rows())
    throw InputError(path + ": the polygons' fans have " + std::to_string(triangles) + " triangles and " +
                     std::to_string(chart.size()) + " chart ids are given; the mesh has " +
                     std::to_string(F.rows()) + " triangles");
  CornerFaces faces;
  faces.first = polygons.first;
  faces.vertex = polygons.vertex;
  faces.uv.resize(static_cast<Eigen::Index>(polygons.vertex.size()), 2);
  Eigen::Index t0 = 0; // the polygon's first triangle: its fan is (c0, ci, ci+1), i = 1 .. n - 2
  for (int p = 0; p < polygons.size(); ++p) {
    const int n = polygons.corners(p);
    for (int j = 0; j < n; ++j) {
      // The triangle corners at polygon corner j; the first in a chart wins (a triangle without an area
      // is in none, its corners put on one point).
      std::vector<Eigen::Index> at;
      if (j == 0)
        for (int i = 0; i < n - 2; ++i) at.push_back(3 * (t0 + i));
      if (j >= 2) at.push_back(3 * (t0 + j - 2) + 2);
      if (j >= 1 && j <= n - 2) at.push_back(3 * (t0 + j - 1) + 1);
      Eigen::Index best = at.front();
      for (Eigen::Index c : at)
        if (chart(c / 3) >= 0) {
          best = c;
          break;
        }
      faces.uv.row(polygons.first[static_cast<std::size_t>(p)] + j) = corner_uv.row(best);
    }
    t0 += n - 2;
  }
  write_corner_faces(path, extension, V, faces);
}

} // namespace iarap
