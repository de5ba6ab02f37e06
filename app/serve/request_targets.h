// Where a solve request sends the constrained vertices and soft points, and the forces it adds: the anchors
// moved by its affine transform, or its explicit handle targets; the statics of `iarap deform`.
#pragma once
#include "constraint_history.h"
#include "solve_request.h"

#include "iarap/io/read_mesh.h"

#include <Eigen/Core>

namespace iarap::serve {

// anchor: #fixed + #handle x 3 (fixed rows first). The fixed rows stay; the last handle_count rows are moved
// by request.transform or replaced by request.handle_targets. Throws InputError for both given, a
// non-finite or non-affine transform (last row 0 0 0 1 to 1e-9 of its scale), or handle targets of the
// wrong count or not finite (naming the row).
Eigen::MatrixXd constrained_targets(const Eigen::MatrixXd& anchor, Eigen::Index handle_count,
                                    const SolveRequest& request);

// soft_anchor: #soft points x 3 in the solver's order. The dragged soft vertices move with the handle's
// transform; the other points keep their anchors. Explicit handle_targets cannot say where a dragged soft
// vertex goes: InputError then. The transform must have passed constrained_targets' checks.
Eigen::MatrixXd soft_point_targets(const Eigen::MatrixXd& soft_anchor, const SoftSession& soft,
                                   const SolveRequest& request);

// The request's statics as `iarap deform`'s (static_forces on the mesh in its own units, s = 1): #V x 3, or
// 0 x 0 without gravity and forces. Every connected component must be held by a constrained vertex or a
// soft point (a free body under a net force has no minimum): TopologyError naming it otherwise; InputError
// for forces of the wrong length.
Eigen::MatrixXd request_forces(const MeshData& mesh, const Eigen::VectorXi& constrained,
                               const SoftConstraintSet& soft, const SolveRequest& request);

} // namespace iarap::serve
