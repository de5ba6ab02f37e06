// The rasterizer is a plain edge-function scan over each triangle's bounding box (pixel centres, top-left
// ties not needed: neighbours overwrite each other's shared samples with the same texture), with a float
// canvas at supersample resolution box-filtered into the 8-bit image at the end.
#include "iarap/param/render_uv_picture.h"

#include "../io/writer_support.h"

#include "iarap/core/errors.h"

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace iarap {

namespace {

using Colour = Eigen::Vector3f;

Colour colour_of(const std::uint8_t (&c)[3]) {
  return Colour(c[0], c[1], c[2]);
}

// An RGB float canvas with a depth buffer, `width` x `height` samples, rows from the top.
struct Canvas {
  int width = 0, height = 0;
  std::vector<Colour> rgb;
  std::vector<float> depth;
  Canvas(int w, int h, const Colour& background)
      : width(w), height(h), rgb(static_cast<std::size_t>(w) * h, background),
        depth(static_cast<std::size_t>(w) * h, -INFINITY) {}
  std::size_t at(int x, int y) const { return static_cast<std::size_t>(y) * width + x; }
};

// Calls shade(x, y, b) for every sample (x, y) in [x0, x1) x [0, height) whose centre lies in the
// triangle a, b, c (sample coordinates, either orientation), b its barycentric coordinates.
template <class Shade>
void scan_triangle(const Canvas& canvas, int x0, int x1, const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                   const Eigen::Vector2d& c, Shade&& shade) {
  const double area = (b - a).x() * (c - a).y() - (b - a).y() * (c - a).x();
  if (!(std::abs(area) > 0)) return;
  const int left = std::max(x0, static_cast<int>(std::floor(std::min({a.x(), b.x(), c.x()}))));
  const int right = std::min(x1 - 1, static_cast<int>(std::ceil(std::max({a.x(), b.x(), c.x()}))));
  const int top = std::max(0, static_cast<int>(std::floor(std::min({a.y(), b.y(), c.y()}))));
  const int bottom =
      std::min(canvas.height - 1, static_cast<int>(std::ceil(std::max({a.y(), b.y(), c.y()}))));
  const auto edge = [](const Eigen::Vector2d& p, const Eigen::Vector2d& q, double x, double y) {
    return (q.x() - p.x()) * (y - p.y()) - (q.y() - p.y()) * (x - p.x());
  };
  for (int y = top; y <= bottom; ++y)
    for (int x = left; x <= right; ++x) {
      const double px = x + 0.5, py = y + 0.5;
      const Eigen::Vector3d w(edge(b, c, px, py) / area, edge(c, a, px, py) / area,
                              edge(a, b, px, py) / area);
      if (w.minCoeff() >= 0) shade(x, y, w);
    }
}

// Marks the samples on segment p q (a DDA step per sample along the longer axis).
void mark_segment(std::vector<char>& mask, const Canvas& canvas, const Eigen::Vector2d& p,
                  const Eigen::Vector2d& q) {
  const double steps = std::ceil(std::max(std::abs(q.x() - p.x()), std::abs(q.y() - p.y())));
  for (int s = 0; s <= static_cast<int>(steps); ++s) {
    const Eigen::Vector2d r = steps > 0 ? p + (q - p) * (s / steps) : p;
    const int x = static_cast<int>(std::floor(r.x())), y = static_cast<int>(std::floor(r.y()));
    if (x >= 0 && x < canvas.width && y >= 0 && y < canvas.height) mask[canvas.at(x, y)] = 1;
  }
}

// Maps points of a 2D bounding box into a square of `side` samples starting at column `x0`, with a margin,
// centred, y up.
struct SquareFit {
  Eigen::Vector2d low, centre;
  double scale = 1;
  int x0 = 0, side = 0;
  SquareFit(const Eigen::Vector2d& lo, const Eigen::Vector2d& hi, int x0_, int side_) : x0(x0_), side(side_) {
    low = lo;
    centre = 0.5 * (lo + hi);
    scale = 0.92 * side / std::max((hi - lo).maxCoeff(), 1e-300);
  }
  Eigen::Vector2d operator()(const Eigen::Vector2d& p) const {
    const Eigen::Vector2d q = (p - centre) * scale;
    return Eigen::Vector2d(x0 + 0.5 * side + q.x(), 0.5 * side - q.y());
  }
};

// The checkerboard over the UV bounding box: squares of side `square` starting at `low`.
struct Checker {
  Eigen::Vector2d low;
  double square = 1;
  Colour light = colour_of(UvPictureColours::light), dark = colour_of(UvPictureColours::dark);
  const Colour& operator()(const Eigen::Vector2d& uv) const {
    const long i = static_cast<long>(std::floor((uv.x() - low.x()) / square));
    const long j = static_cast<long>(std::floor((uv.y() - low.y()) / square));
    return ((i + j) % 2 == 0) ? light : dark;
  }
};

bool is_flipped(const Eigen::MatrixXd& UV, const Eigen::MatrixXi& F, Eigen::Index f) {
  const Eigen::Vector2d a = UV.row(F(f, 0)), b = UV.row(F(f, 1)), c = UV.row(F(f, 2));
  return (b - a).x() * (c - a).y() - (b - a).y() * (c - a).x() <= 0; // det J has the sign of the UV area
}

void check_inputs(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, const Eigen::MatrixXd& UV,
                  const UvPictureOptions& options) {
  const std::string what = "render_uv_picture";
  io_detail::check_mesh_arrays(what, V, F);
  if (UV.rows() != V.rows() || UV.cols() != 2)
    throw InputError(what + ": UV must be #V x 2 = " + std::to_string(V.rows()) + " x 2; got " +
                     std::to_string(UV.rows()) + " x " + std::to_string(UV.cols()));
  for (Eigen::Index v = 0; v < V.rows(); ++v)
    if (!V.row(v).allFinite() || !UV.row(v).allFinite())
      throw InputError(what + ": vertex " + std::to_string(v) + " has a coordinate that is not finite (" +
                       (V.row(v).allFinite() ? "UV" : "position") + ")");
  if (V.rows() > 0 && (UV.colwise().maxCoeff() - UV.colwise().minCoeff()).maxCoeff() <= 0)
    throw InputError(what + ": the UV map has no extent (every vertex at one point)");
  const auto check_range = [&](const char* name, int value, int low, int high) {
    if (value < low || value > high)
      throw InputError(what + ": " + name + " must be in [" + std::to_string(low) + ", " +
                       std::to_string(high) + "]; got " + std::to_string(value));
  };
  check_range("height", options.height, 16, 8192);
  check_range("checker_squares", options.checker_squares, 1, 1024);
  check_range("supersample", options.supersample, 1, 4);
}

void draw_layout(Canvas& canvas, const Eigen::MatrixXi& F, const Eigen::MatrixXd& UV, const SquareFit& fit,
                 const Checker& checker) {
  const Colour red = colour_of(UvPictureColours::flipped);
  std::vector<Eigen::Vector2d> P(static_cast<std::size_t>(UV.rows()));
  for (Eigen::Index v = 0; v < UV.rows(); ++v) P[v] = fit(UV.row(v).transpose());
  // The checkerboard first, the flipped triangles over it (they overlap their neighbours), the edges last.
  for (const bool flipped_pass : {false, true})
    for (Eigen::Index f = 0; f < F.rows(); ++f) {
      if (is_flipped(UV, F, f) != flipped_pass) continue;
      const Eigen::Vector2d &a = P[F(f, 0)], &b = P[F(f, 1)], &c = P[F(f, 2)];
      scan_triangle(canvas, 0, fit.x0 + fit.side, a, b, c, [&](int x, int y, const Eigen::Vector3d& w) {
        const Eigen::Vector2d uv = w(0) * UV.row(F(f, 0)) + w(1) * UV.row(F(f, 1)) + w(2) * UV.row(F(f, 2));
        canvas.rgb[canvas.at(x, y)] = flipped_pass ? red : checker(uv);
      });
    }
  // Each edge blended once (a shared edge drawn twice would come out darker than a boundary one).
  std::vector<char> mask(canvas.rgb.size(), 0);
  for (Eigen::Index f = 0; f < F.rows(); ++f)
    for (int k = 0; k < 3; ++k) mark_segment(mask, canvas, P[F(f, k)], P[F(f, (k + 1) % 3)]);
  const Colour edge = colour_of(UvPictureColours::edge);
  for (std::size_t s = 0; s < mask.size(); ++s)
    if (mask[s]) canvas.rgb[s] = 0.45f * canvas.rgb[s] + 0.55f * edge;
}

// The eye's frame: rows right, up, towards the eye.
Eigen::Matrix3d view_frame(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F) {
  Eigen::Vector3d normal_sum = Eigen::Vector3d::Zero();
  double area_sum = 0;
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    const Eigen::Vector3d a = V.row(F(f, 0)), b = V.row(F(f, 1)), c = V.row(F(f, 2));
    const Eigen::Vector3d n = (b - a).cross(c - a);
    normal_sum += n;
    area_sum += n.norm();
  }
  Eigen::Vector3d towards_eye;
  if (normal_sum.norm() > 0.25 * area_sum) {
    towards_eye = normal_sum.normalized();
  } else {
    const Eigen::MatrixXd centred = V.rowwise() - V.colwise().mean();
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> pca(centred.transpose() * centred);
    towards_eye = pca.eigenvectors().col(0); // least variance
    if (towards_eye.dot(normal_sum) < 0) towards_eye = -towards_eye;
  }
  Eigen::Vector3d up = Eigen::Vector3d::UnitY() - towards_eye.y() * towards_eye;
  if (up.norm() < 0.3) up = Eigen::Vector3d::UnitZ() - towards_eye.z() * towards_eye;
  up.normalize();
  Eigen::Matrix3d frame;
  frame.row(0) = up.cross(towards_eye).normalized();
  frame.row(1) = towards_eye.cross(frame.row(0).transpose());
  frame.row(2) = towards_eye;
  return frame;
}

void draw_surface(Canvas& canvas, const Eigen::MatrixXd& V, const Eigen::MatrixXi& F,
                  const Eigen::MatrixXd& UV, int x0, int side, const Checker& checker) {
  const Eigen::Matrix3d frame = view_frame(V, F);
  const Eigen::MatrixXd E = V * frame.transpose(); // eye coordinates: x right, y up, z towards the eye
  const SquareFit fit(E.leftCols<2>().colwise().minCoeff().transpose(),
                      E.leftCols<2>().colwise().maxCoeff().transpose(), x0, side);
  const Eigen::Vector3d light = Eigen::Vector3d(0.25, 0.35, 1).normalized(); // above right of the eye
  const Colour red = colour_of(UvPictureColours::flipped);
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    const Eigen::Vector3d a = E.row(F(f, 0)), b = E.row(F(f, 1)), c = E.row(F(f, 2));
    const Eigen::Vector3d n = (b - a).cross(c - a);
    if (!(n.norm() > 0)) continue;
    const float lambert = static_cast<float>(0.22 + 0.78 * std::abs(n.normalized().dot(light)));
    const bool flipped = is_flipped(UV, F, f);
    scan_triangle(canvas, x0, x0 + side, fit(a.head<2>()), fit(b.head<2>()), fit(c.head<2>()),
                  [&](int x, int y, const Eigen::Vector3d& w) {
                    const float z = static_cast<float>(w(0) * a.z() + w(1) * b.z() + w(2) * c.z());
                    const std::size_t s = canvas.at(x, y);
                    if (z <= canvas.depth[s]) return;
                    canvas.depth[s] = z;
                    const Eigen::Vector2d uv =
                        w(0) * UV.row(F(f, 0)) + w(1) * UV.row(F(f, 1)) + w(2) * UV.row(F(f, 2));
                    canvas.rgb[s] = lambert * (flipped ? red : checker(uv));
                  });
  }
}

RgbImage downsample(const Canvas& canvas, int factor) {
  RgbImage image;
  image.width = canvas.width / factor;
  image.height = canvas.height / factor;
  image.rgb.resize(3 * static_cast<std::size_t>(image.width) * image.height);
  const float weight = 1.0f / static_cast<float>(factor * factor);
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      Colour sum = Colour::Zero();
      for (int dy = 0; dy < factor; ++dy)
        for (int dx = 0; dx < factor; ++dx) sum += canvas.rgb[canvas.at(factor * x + dx, factor * y + dy)];
      for (int k = 0; k < 3; ++k)
        image.rgb[3 * (static_cast<std::size_t>(y) * image.width + x) + k] =
            static_cast<std::uint8_t>(std::clamp(std::lround(sum(k) * weight), 0L, 255L));
    }
  return image;
}

} // namespace

RgbImage render_uv_picture(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, const Eigen::MatrixXd& UV,
                           const UvPictureOptions& options) {
  check_inputs(V, F, UV, options);
  const int side = options.height * options.supersample;
  Canvas canvas(2 * side, side, colour_of(UvPictureColours::background));
  if (F.rows() == 0) return downsample(canvas, options.supersample);
  const Eigen::Vector2d low = UV.colwise().minCoeff().transpose(), high = UV.colwise().maxCoeff().transpose();
  Checker checker;
  checker.low = low;
  checker.square = (high - low).maxCoeff() / options.checker_squares;
  draw_layout(canvas, F, UV, SquareFit(low, high, 0, side), checker);
  draw_surface(canvas, V, F, UV, side, side, checker);
  return downsample(canvas, options.supersample);
}

} // namespace iarap
