#include "iarap/param/write_uv_map.h"

#include "../io/atomic_file.h"
#include "../io/file_extension.h"
#include "../io/writer_support.h"

#include "iarap/core/errors.h"

#include <map>
#include <tuple>

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

void write_uv_atlas(const std::string& path, const Eigen::MatrixXd& V, const Eigen::MatrixXi& F,
                    const Eigen::MatrixXd& corner_uv) {
  const std::string extension = checked_uv_extension(path, V, F, "a UV atlas");
  if (corner_uv.rows() != 3 * F.rows() || corner_uv.cols() != 2)
    throw InputError(path + ": corner UVs must be (3 #F) x 2 = " + std::to_string(3 * F.rows()) +
                     " x 2; got " + std::to_string(corner_uv.rows()) + " x " +
                     std::to_string(corner_uv.cols()));
  std::string out;
  auto append_uv = [&out](const char* prefix, double u, double v) {
    out += prefix;
    io_detail::append_double(out, u);
    out += ' ';
    io_detail::append_double(out, v);
    out += '\n';
  };
  if (extension == ".txt") {
    out.reserve(static_cast<std::size_t>(corner_uv.rows() * 48));
    for (Eigen::Index c = 0; c < corner_uv.rows(); ++c) append_uv("", corner_uv(c, 0), corner_uv(c, 1));
    io_detail::write_file_atomically(path, out);
    return;
  }
  out.reserve(static_cast<std::size_t>(V.rows() * 110 + F.rows() * 130));
  out += "# UV atlas written by iarap\n";
  io_detail::append_vertex_lines(out, V, "v ");
  std::map<std::tuple<int, double, double>, int> texture_index; // (vertex, u, v) -> vt index from 0
  Eigen::MatrixXi corner_vt(F.rows(), 3);
  for (Eigen::Index f = 0; f < F.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      const Eigen::Index c = 3 * f + k;
      const auto key = std::make_tuple(F(f, k), corner_uv(c, 0), corner_uv(c, 1));
      auto [it, added] = texture_index.emplace(key, static_cast<int>(texture_index.size()));
      if (added) append_uv("vt ", corner_uv(c, 0), corner_uv(c, 1));
      corner_vt(f, k) = it->second;
    }
  append_textured_faces(out, F, corner_vt);
  io_detail::write_file_atomically(path, out);
}

} // namespace iarap
