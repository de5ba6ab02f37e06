// A picture of a UV map: the layout in the plane beside the surface textured through it, both with the
// same checkerboard, for a user to see at a glance where the map stretches, shears or folds over.
//
// Left half: the triangles in UV space filled with the checkerboard (a square texture over the UV bounding
// box), edges drawn thin, flipped triangles (det J <= 0, i.e. clockwise in UV) filled red on top; white
// outside the layout. Right half: the mesh drawn by a software rasterizer (z-buffer, orthographic, flat
// two-sided Lambert shading under a light near the eye) with the same checkerboard looked up through UV,
// flipped triangles red. The view looks at the front of the surface: along its area-weighted mean normal
// when the normals mostly agree (a disk), else along the vertices' axis of least variance; up is the
// mesh's +y (else +z) seen in that view, so that meshes modelled y-up stand upright.
#pragma once
#include "iarap/io/write_png.h"

#include <Eigen/Core>

#include <cstdint>

namespace iarap {

struct UvPictureOptions {
  int height = 800;         // pixels; the picture is 2 * height wide. 16 to 8192.
  int checker_squares = 16; // checkerboard squares along the longer side of the UV bounding box; 1 to 1024.
  int supersample = 2;      // rendered at supersample^2 samples a pixel, box-filtered down; 1 to 4.
};

// The colours, for tests and for the docs.
struct UvPictureColours {
  static constexpr std::uint8_t background[3] = {255, 255, 255};
  static constexpr std::uint8_t light[3] = {236, 232, 220}; // checkerboard square with even u + v index
  static constexpr std::uint8_t dark[3] = {66, 98, 158};    // the other squares
  static constexpr std::uint8_t flipped[3] = {222, 36, 36}; // triangles with det J <= 0
  static constexpr std::uint8_t edge[3] = {24, 24, 24};     // UV edges, blended over the fill
};

// The picture of UV (#V x 2) on the surface (V #V x 3, F #F x 3). Throws InputError when the shapes
// disagree, an index is out of range, a coordinate is not finite, the UV map has no extent (all vertices
// at one point) or an option is out of its range.
RgbImage render_uv_picture(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, const Eigen::MatrixXd& UV,
                           const UvPictureOptions& options = {});

} // namespace iarap
