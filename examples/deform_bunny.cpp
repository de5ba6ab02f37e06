// A complete minimal program on the iarap library: read a mesh, fix its bottom, lift one side of its top,
// deform it with each of the three ARAP energies and write the iARAP result.
//
//   deform_bunny MESH OUT      (e.g. data/bunny.off out/bunny_deformed.off)
//
// Built by the top-level CMake build (target deform_bunny, run by CTest as example_deform_bunny), or
// alone against an installed iarap: cmake -S examples -B build-example -DCMAKE_PREFIX_PATH=<prefix>.
#include <iarap/core/errors.h>
#include <iarap/core/version.h>
#include <iarap/io/read_mesh.h>
#include <iarap/io/write_mesh.h>
#include <iarap/solver/arap.h>

#include <iostream>
#include <vector>

int main(int argc, char** argv) {
  if (argc != 3) {
    std::cerr << "usage: deform_bunny MESH OUT\n";
    return 2;
  }
  try {
    const iarap::MeshData mesh = iarap::read_mesh(argv[1]);

    // Constraints: the lowest 10% of the bounding box (along y) stays, the highest 10% moves along +x by
    // a tenth of the bounding-box diagonal. targets[k] is where fixed[k] goes.
    const double low = mesh.V.col(1).minCoeff(), high = mesh.V.col(1).maxCoeff();
    const double diagonal = (mesh.V.colwise().maxCoeff() - mesh.V.colwise().minCoeff()).norm();
    std::vector<int> bottom, top;
    for (int v = 0; v < mesh.V.rows(); ++v) {
      if (mesh.V(v, 1) <= low + 0.1 * (high - low))
        bottom.push_back(v);
      else if (mesh.V(v, 1) >= high - 0.1 * (high - low))
        top.push_back(v);
    }
    Eigen::VectorXi fixed(static_cast<Eigen::Index>(bottom.size() + top.size()));
    Eigen::MatrixXd targets(fixed.size(), 3);
    for (std::size_t k = 0; k < bottom.size() + top.size(); ++k) {
      const bool moved = k >= bottom.size();
      fixed(static_cast<Eigen::Index>(k)) = moved ? top[k - bottom.size()] : bottom[k];
      targets.row(static_cast<Eigen::Index>(k)) = mesh.V.row(fixed(static_cast<Eigen::Index>(k)));
      if (moved) targets(static_cast<Eigen::Index>(k), 0) += 0.1 * diagonal;
    }

    std::cout << "iarap " << iarap::version() << ": " << mesh.V.rows() << " vertices, " << mesh.F.rows()
              << " faces, " << bottom.size() << " fixed, " << top.size() << " moved\n";
    Eigen::MatrixXd result;
    for (const char* name : {"arap", "spokes-rims", "iarap"}) {
      iarap::ArapOptions options;
      options.method = iarap::parse_arap_method(name);
      // Set up once per mesh and constrained set: elements, the system matrix, its factorization.
      iarap::ArapData data = iarap::arap_precompute(mesh.V, mesh.F, fixed, options);
      Eigen::MatrixXd U = mesh.V; // initial guess: the rest shape
      iarap::ArapSolveOptions solve;
      solve.max_iterations = 30;
      const iarap::ArapReport report = iarap::arap_solve(data, targets, U, solve);
      std::cout << name << ": energy " << report.initial_energy << " -> " << report.energies.back()
                << " after " << report.iterations << " iterations\n";
      result = U;
    }
    iarap::write_mesh(argv[2], result, mesh.F); // the iARAP result (the last method), written atomically
    std::cout << "wrote " << argv[2] << "\n";
  } catch (const iarap::Error& e) { // InputError, TopologyError, SolverError: the message names the culprit
    std::cerr << "deform_bunny: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
