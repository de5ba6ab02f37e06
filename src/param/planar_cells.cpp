#include "iarap/param/planar_cells.h"

#include "iarap/core/errors.h"
#include "iarap/solver/closest_rotation_2d.h"

#include <Eigen/Geometry>
#include <cmath>
#include <string>

namespace iarap {

namespace {

// Unit t1, t2 with t1 x t2 = n / |n|, t1 along the coordinate axis least aligned with n projected.
void tangent_frame(const Eigen::Vector3d& n, Eigen::Vector3d& t1, Eigen::Vector3d& t2) {
  const Eigen::Vector3d unit = n.normalized();
  Eigen::Index axis = 0;
  unit.cwiseAbs().minCoeff(&axis);
  const Eigen::Vector3d e = Eigen::Vector3d::Unit(axis);
  t1 = (e - e.dot(unit) * unit).normalized();
  t2 = unit.cross(t1);
}

// UV^T b_e: element e under the map.
Eigen::Vector2d deformed(const ArapElements& elements, Eigen::Index e, const Eigen::MatrixXd& UV) {
  Eigen::Vector2d x = Eigen::Vector2d::Zero();
  for (int j = 0; j < 3; ++j) x += elements.b_value(e, j) * UV.row(elements.b_index(e, j)).transpose();
  return x;
}

Eigen::Matrix2d row_matrix(const Eigen::MatrixXd& rows, Eigen::Index c) {
  Eigen::Matrix2d M;
  M << rows(c, 0), rows(c, 1), rows(c, 2), rows(c, 3);
  return M;
}

} // namespace

PlanarCells planar_cells(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, ArapElements elements) {
  const Eigen::Index n = V.rows();
  if (elements.num_cells != n || elements.num_vertices != n)
    throw InputError("planar cells need one rotation cell per vertex; the elements have " +
                     std::to_string(elements.num_cells) + " cells for " + std::to_string(n) + " vertices");
  Eigen::MatrixXd normal = Eigen::MatrixXd::Zero(n, 3);
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    const Eigen::Vector3d a = V.row(F(f, 0)), b = V.row(F(f, 1)), c = V.row(F(f, 2));
    const Eigen::RowVector3d twice_area_normal = (b - a).cross(c - a).transpose();
    for (int k = 0; k < 3; ++k) normal.row(F(f, k)) += twice_area_normal;
  }
  PlanarCells cells;
  cells.frame.resize(n, 6);
  for (Eigen::Index v = 0; v < n; ++v) {
    if (!(normal.row(v).norm() > 0))
      throw InputError("vertex " + std::to_string(v) +
                       " has no face with an area: its cell has no tangent plane");
    Eigen::Vector3d t1, t2;
    tangent_frame(normal.row(v).transpose(), t1, t2);
    cells.frame.row(v) << t1.transpose(), t2.transpose();
  }
  cells.s.resize(static_cast<Eigen::Index>(elements.cell.size()), 2);
  for (Eigen::Index e = 0; e < elements.size(); ++e) {
    const Eigen::Vector3d rest = elements.s_hat.row(e).transpose();
    for (int k = elements.cell_start[static_cast<std::size_t>(e)];
         k < elements.cell_start[static_cast<std::size_t>(e) + 1]; ++k) {
      const int c = elements.cell[static_cast<std::size_t>(k)];
      Eigen::Vector2d flat(cells.frame.row(c).head<3>().dot(rest.transpose()),
                           cells.frame.row(c).tail<3>().dot(rest.transpose()));
      const double length = flat.norm();
      if (length > 0) flat *= rest.norm() / length;
      cells.s.row(k) = flat.transpose();
    }
  }
  cells.elements = std::move(elements);
  return cells;
}

void planar_cell_covariances(const PlanarCells& cells, const Eigen::MatrixXd& UV, Eigen::MatrixXd& S) {
  const ArapElements& el = cells.elements;
  S.setZero(el.num_cells, 4);
  for (Eigen::Index e = 0; e < el.size(); ++e) {
    const Eigen::Vector2d x = deformed(el, e, UV);
    for (int k = el.cell_start[static_cast<std::size_t>(e)];
         k < el.cell_start[static_cast<std::size_t>(e) + 1]; ++k) {
      const double half_w = 0.5 * el.w(e), s0 = cells.s(k, 0), s1 = cells.s(k, 1);
      auto Sc = S.row(el.cell[static_cast<std::size_t>(k)]);
      Sc(0) += half_w * x(0) * s0;
      Sc(1) += half_w * x(0) * s1;
      Sc(2) += half_w * x(1) * s0;
      Sc(3) += half_w * x(1) * s1;
    }
  }
}

double planar_cell_energy(const PlanarCells& cells, const Eigen::MatrixXd& UV, Eigen::MatrixXd& R) {
  const ArapElements& el = cells.elements;
  Eigen::MatrixXd covariance;
  planar_cell_covariances(cells, UV, covariance);
  R.resize(el.num_cells, 4);
  for (Eigen::Index c = 0; c < el.num_cells; ++c) {
    const Eigen::Matrix2d Rc = closest_rotation_2d(row_matrix(covariance, c));
    R.row(c) << Rc(0, 0), Rc(0, 1), Rc(1, 0), Rc(1, 1);
  }
  return planar_cell_energy_at(cells, UV, R);
}

double planar_cell_energy_at(const PlanarCells& cells, const Eigen::MatrixXd& UV, const Eigen::MatrixXd& R) {
  const ArapElements& el = cells.elements;
  double energy = 0;
  for (Eigen::Index e = 0; e < el.size(); ++e) {
    const Eigen::Vector2d x = deformed(el, e, UV);
    for (int k = el.cell_start[static_cast<std::size_t>(e)];
         k < el.cell_start[static_cast<std::size_t>(e) + 1]; ++k) {
      const Eigen::Matrix2d Rc = row_matrix(R, el.cell[static_cast<std::size_t>(k)]);
      energy += 0.5 * el.w(e) * (x - Rc * cells.s.row(k).transpose()).squaredNorm();
    }
  }
  return energy;
}

double planar_cell_energy(const PlanarCells& cells, const Eigen::MatrixXd& UV) {
  Eigen::MatrixXd R;
  return planar_cell_energy(cells, UV, R);
}

void planar_cell_rhs(const PlanarCells& cells, const Eigen::MatrixXd& R, Eigen::MatrixXd& r) {
  const ArapElements& el = cells.elements;
  r.setZero(el.num_vertices, 2);
  for (Eigen::Index e = 0; e < el.size(); ++e)
    for (int k = el.cell_start[static_cast<std::size_t>(e)];
         k < el.cell_start[static_cast<std::size_t>(e) + 1]; ++k) {
      const Eigen::Vector2d rotated =
          row_matrix(R, el.cell[static_cast<std::size_t>(k)]) * cells.s.row(k).transpose();
      for (int j = 0; j < 3; ++j)
        r.row(el.b_index(e, j)) += (0.5 * el.w(e) * el.b_value(e, j)) * rotated.transpose();
    }
}

} // namespace iarap
