#include "iarap/registration/registration_target.h"

#include "../io/file_extension.h"
#include "../scene/line_tokens.h"
#include "iarap/core/errors.h"
#include "iarap/io/read_mesh.h"
#include "iarap/registration/surface_normals.h"

#include <cmath>
#include <fstream>
#include <string>
#include <vector>

namespace iarap {

namespace {

std::string row_text(const Eigen::MatrixXd& M, Eigen::Index i) {
  return std::to_string(M(i, 0)) + " " + std::to_string(M(i, 1)) + " " + std::to_string(M(i, 2));
}

void check_points(const Eigen::MatrixXd& points, const std::string& source) {
  if (points.cols() != 3) throw InputError(source + ": target points must be #P x 3");
  if (points.rows() == 0) throw InputError(source + ": the target has no point");
  for (Eigen::Index i = 0; i < points.rows(); ++i) {
    if (!points.row(i).allFinite())
      throw InputError(source + ": target point " + std::to_string(i) + " is not finite (" +
                       row_text(points, i) + ")");
  }
  if ((points.rowwise() - points.row(0)).rowwise().squaredNorm().maxCoeff() == 0)
    throw InputError(source + ": all " + std::to_string(points.rows()) + " target points coincide");
}

void check_faces(const Eigen::MatrixXi& faces, Eigen::Index num_points, const std::string& source) {
  if (faces.size() > 0 && faces.cols() != 3) throw InputError(source + ": target faces must be #F x 3");
  for (Eigen::Index f = 0; f < faces.rows(); ++f)
    for (int k = 0; k < 3; ++k)
      if (faces(f, k) < 0 || faces(f, k) >= num_points)
        throw InputError(source + ": target face " + std::to_string(f) + " uses point " +
                         std::to_string(faces(f, k)) + "; the target has " + std::to_string(num_points));
}

void check_normals(const Eigen::MatrixXd& normals, Eigen::Index num_points, const std::string& source) {
  if (normals.rows() != num_points || normals.cols() != 3) {
    throw InputError(source + ": target normals must be #P x 3 (" + std::to_string(num_points) +
                     " x 3); got " + std::to_string(normals.rows()) + " x " + std::to_string(normals.cols()));
  }
  for (Eigen::Index i = 0; i < normals.rows(); ++i) {
    if (!normals.row(i).allFinite() || normals.row(i).norm() == 0)
      throw InputError(source + ": target normal " + std::to_string(i) +
                       " is not a finite non-zero vector (" + row_text(normals, i) + ")");
  }
}

// '.xyz': 'x y z' or 'x y z nx ny nz' per line.
void read_xyz(const std::string& path, Eigen::MatrixXd& points, Eigen::MatrixXd& normals) {
  std::ifstream in(path);
  if (!in) throw InputError(path + ": cannot open point cloud file");
  std::vector<double> values;
  std::string text;
  std::size_t columns = 0;
  int first_line = 0;
  for (int line = 1; std::getline(in, text); ++line) {
    const std::size_t hash = text.find('#');
    if (hash != std::string::npos) text.erase(hash);
    const std::vector<std::string> tokens = detail::tokens_of(text);
    if (tokens.empty()) continue;
    const std::string at = detail::where(path, line);
    if (tokens.size() != 3 && tokens.size() != 6)
      throw InputError(at + "expected 'x y z' or 'x y z nx ny nz', found " + std::to_string(tokens.size()) +
                       " values");
    if (columns == 0) {
      columns = tokens.size();
      first_line = line;
    } else if (tokens.size() != columns) {
      throw InputError(at + std::to_string(tokens.size()) + " values, but line " +
                       std::to_string(first_line) + " has " + std::to_string(columns));
    }
    static const char* const names[] = {"x", "y", "z", "nx", "ny", "nz"};
    for (std::size_t k = 0; k < tokens.size(); ++k)
      values.push_back(detail::parse_coordinate(tokens[k], at, names[k]));
    if (columns == 6 && values[values.size() - 1] == 0 && values[values.size() - 2] == 0 &&
        values[values.size() - 3] == 0)
      throw InputError(at + "zero normal");
  }
  if (columns == 0) throw InputError(path + ": the point cloud has no point");
  const auto n = static_cast<Eigen::Index>(values.size() / columns);
  const Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>> all(
      values.data(), n, static_cast<Eigen::Index>(columns));
  points = all.leftCols(3);
  normals = columns == 6 ? Eigen::MatrixXd(all.rightCols(3)) : Eigen::MatrixXd();
}

} // namespace

RegistrationTarget make_registration_target(Eigen::MatrixXd points, Eigen::MatrixXd normals,
                                            Eigen::MatrixXi faces, const std::string& source,
                                            int normal_neighbours) {
  check_points(points, source);
  if (faces.size() == 0) faces.resize(0, 3);
  check_faces(faces, points.rows(), source);
  RegistrationTarget target;
  target.index = PointIndex(points);
  target.around = vertex_faces(faces, points.rows());
  if (normals.size() > 0) {
    check_normals(normals, points.rows(), source);
    normals.rowwise().normalize();
  } else if (faces.rows() > 0) {
    normals = area_weighted_vertex_normals(points, faces);
    // A point on no face (or only on zero-area ones) has no mesh normal: PCA of its neighbours instead.
    const bool all_set = (normals.rowwise().squaredNorm().array() > 0).all();
    if (!all_set) {
      const Eigen::MatrixXd estimated =
          estimate_point_normals(points, target.index, normal_neighbours, source);
      for (Eigen::Index i = 0; i < normals.rows(); ++i)
        if (normals.row(i).squaredNorm() == 0) normals.row(i) = estimated.row(i);
    }
  } else {
    normals = estimate_point_normals(points, target.index, normal_neighbours, source);
    target.oriented = false;
  }
  target.diagonal = (points.colwise().maxCoeff() - points.colwise().minCoeff()).norm();
  target.points = std::move(points);
  target.normals = std::move(normals);
  target.faces = std::move(faces);
  return target;
}

RegistrationTarget read_registration_target(const std::string& path, int normal_neighbours) {
  Eigen::MatrixXd points, normals;
  Eigen::MatrixXi faces;
  if (io_detail::lower_extension(path) == ".xyz") {
    read_xyz(path, points, normals);
  } else {
    MeshData mesh = read_mesh(path);
    points = std::move(mesh.V);
    faces = std::move(mesh.F);
  }
  return make_registration_target(std::move(points), std::move(normals), std::move(faces), path,
                                  normal_neighbours);
}

} // namespace iarap
