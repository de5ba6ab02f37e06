// The choices of arap_parameterize: initial map, boundary, the engine's solve options, and their names.
#pragma once
#include "iarap/solver/arap_types.h"

#include <Eigen/Core>
#include <optional>
#include <string>

namespace iarap {

enum class ParamEnergy {
  Triangle, // Liu et al. 2008: sum_f area_f ||J_f - R_f||^2, one rotation per triangle (libigl, CGAL)
  Arap,     // per vertex, original ARAP's cotan edges (Sorkine and Alexa 2007) on flattened cells
  Iarap,    // per vertex, iARAP's intrinsic Delaunay segments (paper Eq. 9, no boundary refinement)
};

enum class ParamInit {
  Lscm,     // least-squares conformal, free boundary (lscm.h)
  Tutte,    // uniform weights, boundary on a circle (fixed_boundary_map.h)
  Harmonic, // cotan weights, boundary on a circle
};

enum class ParamBoundary {
  Free,   // the boundary moves with the iteration; one vertex is pinned (the energy is translation invariant)
  Circle, // every boundary vertex stays where circle_boundary puts it
};

// ArapSolveOptions with the parameterization's defaults: 100 iterations, the rest as for deformation.
ArapSolveOptions default_param_solve_options();

// Vertices held at given UV positions (in the units of V): LSCM's two default pins, or a user's.
struct UvPins {
  Eigen::VectorXi vertices; // #p distinct vertex indices
  Eigen::MatrixXd uv;       // #p x 2: row p, the UV position of vertices(p)
  Eigen::Index size() const { return vertices.size(); }
};

// Throws InputError unless pins has matching shapes (#p indices, #p x 2 positions), indices in
// 0..num_vertices-1 and distinct, and finite positions; messages name the pin ("pin 3 (vertex 17)").
void check_uv_pins(const UvPins& pins, Eigen::Index num_vertices);

struct ParamOptions {
  ParamEnergy energy = ParamEnergy::Triangle; // the per-vertex ones: planar_cells.h
  ParamInit init = ParamInit::Lscm;           // ParamBoundary::Circle needs Tutte or Harmonic
  ParamBoundary boundary = ParamBoundary::Free;
  // false: flip-free. The iteration starts from an injective map (the requested one if it flips no
  // triangle, else Tutte's) and shortens each step so that no triangle's det J reaches 0. true: the plain
  // local/global iteration from the requested initial map, as in libigl and CGAL.
  bool allow_flips = false;
  // The local/global engine's options, as for deformation (arap_types.h): max_iterations (100 here),
  // tolerance (relative energy decrease, CGAL's rule), gradient_tolerance, accelerator (Newton by
  // default; every accelerator keeps a flip-free map flip-free), window, time_budget_ms (counted from the
  // start of arap_parameterize), on_iteration. forces and the Newton warm start do not apply to UV maps.
  ArapSolveOptions solve = default_param_solve_options();
  // The flip-free step is this fraction of the largest step that keeps every det J > 0 (Smith and
  // Schaefer 2015 take 0.8 to 0.9); in (0, 1).
  double step_fraction = 0.8;
  // The flip-free iteration minimizes E + sum_f area_f mu psi(det J_f), psi(x) = -log(x / eps) + x / eps - 1
  // below eps and 0 above: a barrier that only triangles shrunk below eps of their area feel, and that
  // bends the step away from degenerating them. Unset, mu is default_barrier_weight(energy). Measured
  // (docs/param.md): for the triangle energy mu = 1e-3 leaves the steps short (0.01) and 100 iterations end
  // at 0.85 on camelhead, mu = 1e-2 converges in 13 to 71 iterations to within 0.04% of the plain
  // iteration's energy (which flips hundreds of triangles); the per-vertex energies, which do not see a
  // triangle collapse, need mu = 1e-1 (iarap on camelhead: 136-144 iterations to 0.8018 against 266 to 0.8017
  // and 200 not converged with 1e-2). Unused with allow_flips.
  std::optional<double> barrier_weight; // mu > 0
  double barrier_threshold = 1e-1;      // eps > 0, dimensionless (det J is an area ratio)
  // Vertices the map must put at given UV positions, held exactly by every iterate. With the free
  // boundary they replace the one vertex pinned by default: one pin fixes the translation, two also the
  // rotation and scale (the start is the unpinned one moved by the similarity that meets them: injective
  // when it is), three or more also shape the start (LSCM with them held, or with the tutte / harmonic
  // start, the circle map with them as inner vertices). With ParamBoundary::Circle they must be inner
  // vertices, in the circle's coordinates (centre at the origin, radius sqrt(area / pi)), held by the
  // Tutte or harmonic start too. Flip-free, a start that the pins fold is refused (InputError naming the
  // count): pins can demand a fold no iteration undoes, and the flip-free iteration needs an injective start.
  UvPins pins;
  // A start map given by the caller (#V x 2, in the units of V; empty: none), e.g. an OBJ's own texture
  // coordinates or an LSCM map already computed: used instead of `init` when it folds no triangle (or with
  // allow_flips); when it folds one, the flip-free iteration starts from `init` as if it were not given.
  // Only with the free boundary and without pins (InputError otherwise).
  Eigen::MatrixXd initial_uv;
};

// The initial map to use when none is named: lscm for a free boundary, harmonic for a circular one (the
// start must have the boundary the iteration holds).
ParamInit default_param_init(ParamBoundary boundary);

// The barrier weight mu of the flip-free iteration when ParamOptions leaves it unset: 1e-2 for
// ParamEnergy::Triangle, 1e-1 for the per-vertex energies.
double default_barrier_weight(ParamEnergy energy);

// "triangle", "arap", "iarap".
std::string param_energy_name(ParamEnergy energy);
ParamEnergy parse_param_energy(const std::string& name);

// "lscm", "tutte", "harmonic".
std::string param_init_name(ParamInit init);
// The inverse; throws InputError naming the name and the valid ones.
ParamInit parse_param_init(const std::string& name);
// "free", "circle".
std::string param_boundary_name(ParamBoundary boundary);
ParamBoundary parse_param_boundary(const std::string& name);

} // namespace iarap
