// Writing triangle meshes to OBJ, OFF and PLY files, atomically and at full precision.
//
// Every writer checks V (#V x 3) and F (#F x 3, indices in 0..#V-1) first and throws InputError naming the
// offending face otherwise. The file is written to a temporary file in the same folder and renamed over
// `path` only when complete, so readers never see a half-written mesh. Coordinates are printed with
// %.17g (round-trip exact for doubles); binary PLY stores raw doubles. I/O failures throw InputError
// naming the path and the system's reason.
#pragma once
#include <Eigen/Core>
#include <string>

namespace iarap {

enum class PlyEncoding { ascii, binary_little_endian };

// Dispatches on the extension, case-insensitive: .obj .off .ply (ASCII). Throws InputError for others.
void write_mesh(const std::string& path, const Eigen::MatrixXd& V, const Eigen::MatrixXi& F);

void write_obj(const std::string& path, const Eigen::MatrixXd& V, const Eigen::MatrixXi& F);
void write_off(const std::string& path, const Eigen::MatrixXd& V, const Eigen::MatrixXi& F);
// Vertex x, y, z as double; face list as uchar count + int indices.
void write_ply(const std::string& path, const Eigen::MatrixXd& V, const Eigen::MatrixXi& F,
               PlyEncoding encoding = PlyEncoding::ascii);

} // namespace iarap
