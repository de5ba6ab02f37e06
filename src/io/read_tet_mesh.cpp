#include "iarap/io/read_tet_mesh.h"

#include "iarap/core/errors.h"

#include "file_extension.h"
#include "read_tet_mesh_support.h"

#include <algorithm>

namespace iarap {

namespace io_detail {

TokenLines::TokenLines(const std::string& path, std::string_view text, bool hash_comments)
    : path_(path), lines_(text, utf8_bom_length(text)), hash_comments_(hash_comments) {}

bool TokenLines::next(std::vector<std::string_view>& tokens) {
  std::string_view line;
  while (lines_.next(line)) {
    if (hash_comments_) line = line.substr(0, line.find('#'));
    split_tokens(line, tokens);
    if (!tokens.empty()) return true;
  }
  return false;
}

void TokenLines::require(std::vector<std::string_view>& tokens, const std::string& what) {
  if (!next(tokens)) fail_at_line(path_, line(), "unexpected end of file, expected " + what);
}

TokenStream::TokenStream(const std::string& path, std::string_view text, bool hash_comments)
    : lines_(path, text, hash_comments) {}

bool TokenStream::next(std::string_view& token) {
  if (at_ == tokens_.size()) {
    if (!lines_.next(tokens_)) return false;
    at_ = 0;
  }
  token = tokens_[at_++];
  return true;
}

std::string_view TokenStream::require(const std::string& what) {
  std::string_view token;
  if (!next(token)) fail_at_line(path(), line(), "unexpected end of file, expected " + what);
  return token;
}

double parse_coordinate(const std::string& path, std::int64_t line, std::string_view token,
                        const char* what) {
  double value = 0.0;
  if (!parse_double(token, value))
    fail_at_line(path, line, std::string("bad ") + what + " " + quote_token(token) + " (expected a number)");
  return value;
}

std::int64_t parse_count(const std::string& path, std::int64_t line, std::string_view token, const char* what,
                         std::int64_t low, std::int64_t high) {
  std::int64_t value = 0;
  if (!parse_int(token, value))
    fail_at_line(path, line,
                 std::string("bad ") + what + " " + quote_token(token) + " (expected an integer)");
  if (value < low || value > high)
    fail_at_line(path, line,
                 std::string(what) + " " + std::to_string(value) + " is out of range " + std::to_string(low) +
                     ".." + std::to_string(high));
  return value;
}

TetMesh finish_tet_mesh(const std::string& path, TetParse parse, int base) {
  TetMesh mesh;
  const auto n = static_cast<Eigen::Index>(parse.xyz.size() / 3);
  const auto m = static_cast<Eigen::Index>(parse.tets.size() / 4);
  mesh.V =
      Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>>(parse.xyz.data(), n, 3);
  mesh.T.resize(m, 4);
  for (Eigen::Index t = 0; t < m; ++t)
    for (int k = 0; k < 4; ++k) {
      const std::int64_t v = parse.tets[static_cast<size_t>(4 * t + k)];
      if (v < 0 || v >= n)
        fail_at_line(path, parse.tet_line[static_cast<size_t>(t)],
                     "tetrahedron " + std::to_string(t) + " uses vertex index " + std::to_string(v + base) +
                         "; the file has " + std::to_string(n) + " vertices, numbered from " +
                         std::to_string(base));
      mesh.T(t, k) = static_cast<int>(v);
    }
  if (m == 0) throw InputError(path + ": no tetrahedra");
  for (Eigen::Index v = 0; v < n; ++v)
    if (!mesh.V.row(v).allFinite())
      throw InputError(path + ": vertex " + std::to_string(v) + " has a non-finite coordinate");
  const TetProblem problem = find_tet_problem(mesh.V, mesh.T);
  if (problem.tet >= 0) fail_at_line(path, parse.tet_line[static_cast<size_t>(problem.tet)], problem.message);
  // Orientation (tet_mesh.h): one sign for the whole file; all negative is the file's convention.
  const Eigen::VectorXd volume = tet_signed_volumes(mesh.V, mesh.T);
  const Eigen::Index negative = (volume.array() < 0).count();
  if (negative == m) {
    mesh.T.col(2).swap(mesh.T.col(3));
    parse.notes.push_back("reoriented all " + std::to_string(m) +
                          " tetrahedra (the file lists them with negative volume)");
  } else if (negative > 0) {
    const bool minority_negative = 2 * negative <= m;
    Eigen::Index t = 0;
    while ((volume(t) < 0) != minority_negative) ++t;
    fail_at_line(path, parse.tet_line[static_cast<size_t>(t)],
                 "tetrahedron " + std::to_string(t) + " is inverted: its volume is " +
                     (minority_negative ? "negative" : "positive") + " while " +
                     std::to_string(minority_negative ? m - negative : negative) + " of the " +
                     std::to_string(m) + " tetrahedra have the other sign (a tangled mesh)");
  }
  mesh.notes = std::move(parse.notes);
  return mesh;
}

} // namespace io_detail

bool is_tet_mesh_path(const std::string& path) {
  const std::string ext = io_detail::lower_extension(path);
  return ext == ".mesh" || ext == ".node" || ext == ".ele" || ext == ".msh";
}

TetMesh read_tet_mesh(const std::string& path) {
  const std::string ext = io_detail::lower_extension(path);
  if (ext == ".mesh") return read_medit_mesh(path);
  if (ext == ".node" || ext == ".ele") return read_tetgen(path);
  if (ext == ".msh") return read_gmsh(path);
  throw InputError(path + ": unsupported tetrahedral mesh extension '" + ext +
                   "' (readable: .mesh .node .ele .msh)");
}

} // namespace iarap
