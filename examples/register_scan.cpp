// Registration on the iarap library: a mesh bent by a known ARAP deformation plus a smooth warp is sampled as
// a noisy point cloud with a hole and fitted back from its rest shape and a dozen landmarks; the error to
// the known answer is printed for the fit and for the deformation the landmarks alone give.
//
//   register_scan MESH [OUT]      (e.g. ../shared/meshes/cheburashka.off out/fit.off)
//
// Built by the top-level CMake build (target register_scan, run by CTest on data/bunny.off as
// example_register_scan), or alone against an installed iarap like deform_bunny.
#include <iarap/core/errors.h>
#include <iarap/core/stopwatch.h>
#include <iarap/core/threads.h>
#include <iarap/io/read_mesh.h>
#include <iarap/io/write_mesh.h>
#include <iarap/registration/register.h>
#include <iarap/registration/sample_surface.h>
#include <iarap/solver/arap.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <vector>

namespace {

// Mean and 90th percentile of |A_i - B_i| over the rows, as fractions of `diagonal`.
void print_error(const char* what, const Eigen::MatrixXd& A, const Eigen::MatrixXd& B, double diagonal) {
  Eigen::VectorXd e = (A - B).rowwise().norm() / diagonal;
  std::sort(e.data(), e.data() + e.size());
  std::cout << what << ": mean vertex error " << e.mean() << ", 90th percentile "
            << e(static_cast<Eigen::Index>(0.9 * static_cast<double>(e.size() - 1)))
            << " (of the diagonal)\n";
}

} // namespace

int main(int argc, char** argv) {
  if (argc != 2 && argc != 3) {
    std::cerr << "usage: register_scan MESH [OUT]\n";
    return 2;
  }
  try {
    const iarap::MeshData mesh = iarap::read_mesh(argv[1]);
    const Eigen::MatrixXd& V = mesh.V;
    // As the tool: one thread below 10,000 vertices, all above.
    iarap::set_thread_count(iarap::automatic_thread_count(static_cast<int>(V.rows())));
    const Eigen::RowVector3d low = V.colwise().minCoeff(), high = V.colwise().maxCoeff();
    const double diagonal = (high - low).norm(), height = high(1) - low(1);

    // The known answer: the lowest 10% along y fixed, the highest 10% moved by 0.15 of the diagonal along +x
    // (ARAP, converged as `iarap deform` does), then a smooth warp of 2% of the diagonal.
    std::vector<int> handle;
    for (int v = 0; v < V.rows(); ++v)
      if (V(v, 1) <= low(1) + 0.1 * height || V(v, 1) >= high(1) - 0.1 * height) handle.push_back(v);
    const Eigen::VectorXi fixed =
        Eigen::Map<const Eigen::VectorXi>(handle.data(), static_cast<Eigen::Index>(handle.size()));
    Eigen::MatrixXd targets = V(fixed, Eigen::all);
    for (Eigen::Index k = 0; k < fixed.size(); ++k)
      if (V(fixed(k), 1) >= high(1) - 0.1 * height) targets(k, 0) += 0.15 * diagonal;
    double deform_ms = 0;
    Eigen::MatrixXd truth = V;
    {
      const iarap::ScopedTimer timer(deform_ms);
      iarap::ArapData bend = iarap::arap_precompute(V, mesh.F, fixed);
      iarap::arap_solve(bend, targets, truth);
    }
    for (Eigen::Index v = 0; v < V.rows(); ++v) {
      const double y = (V(v, 1) - low(1)) / height;
      truth(v, 2) += 0.02 * diagonal * std::sin(3.0 * y) * std::cos(2.0 * (V(v, 0) - low(0)) / diagonal);
    }

    // The scan: 3 points per vertex, noise of 0.1% of the diagonal, a hole of radius 0.08 around the
    // front-most point.
    const Eigen::MatrixXd samples = iarap::sample_surface(truth, mesh.F, 3 * V.rows(), 46, 0.001 * diagonal);
    Eigen::Index front = 0;
    truth.col(2).maxCoeff(&front);
    std::vector<Eigen::Index> kept;
    for (Eigen::Index i = 0; i < samples.rows(); ++i)
      if ((samples.row(i) - truth.row(front)).norm() > 0.08 * diagonal) kept.push_back(i);
    const iarap::RegistrationTarget scan =
        iarap::make_registration_target(samples(kept, Eigen::all), {}, {}, "scan");

    // Twelve landmarks spread over the vertex numbering, at their known positions.
    iarap::RegistrationLandmarks landmarks;
    landmarks.vertices = Eigen::VectorXi::LinSpaced(12, 0, static_cast<int>(V.rows() - 1));
    landmarks.vertex_targets = truth(landmarks.vertices, Eigen::all);

    iarap::ArapData alone = iarap::arap_precompute(V, mesh.F, landmarks.vertices);
    Eigen::MatrixXd landmarks_only = V;
    iarap::arap_solve(alone, landmarks.vertex_targets, landmarks_only);

    const iarap::RegistrationResult fit = iarap::register_to_target(V, mesh.F, scan, landmarks);
    const iarap::RegistrationReport& report = fit.report;
    const auto rounds = static_cast<double>(report.rounds.size());
    std::cout << "register_scan: " << V.rows() << " vertices, scan of " << scan.points.rows() << " points\n";
    print_error("landmarks only", landmarks_only, truth, diagonal);
    print_error("registered", fit.U, truth, diagonal);
    std::cout << "registered: " << report.rounds.size() << " rounds, per round " << report.closest_ms / rounds
              << " ms closest points, " << report.factor_ms / rounds << " ms refactorization, "
              << report.solve_ms / rounds << " ms solve; total " << report.total_ms << " ms (pre-alignment "
              << report.prealign_ms << " ms, precompute " << report.precompute_ms
              << " ms); the bend alone took " << deform_ms << " ms\n";
    if (argc == 3) {
      iarap::write_mesh(argv[2], fit.U, mesh.F);
      std::cout << "wrote " << argv[2] << "\n";
    }
  } catch (const iarap::Error& e) {
    std::cerr << "register_scan: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
