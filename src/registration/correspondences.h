// Internal: the correspondences of one ICP round, both ways, turned into per-vertex pulls of the source.
//
// Closest points on a target: the k-d tree is over the target's points; for a mesh target the nearest
// vertex is refined to the closest point on the triangles around it. Chosen over a k-d tree of a dense
// sampling of the triangles because it needs no sampling density (a parameter that trades accuracy for
// memory), builds once over data the target already has, and is exact wherever the closest triangle
// touches the nearest vertex (true unless the mesh has long slivers; elsewhere the point found is still on
// the surface and no farther than the vertex).
//
// Forward (source -> target): every source vertex p gets its closest target point q with normal n and the
// soft target (1 - alpha) q + alpha (p - ((p - q) . n) n): point-to-plane as a target moved onto the
// tangent plane's projection (alpha = point_to_plane). Backward (target -> source): every target point q
// gets its closest point p = sum_k b_k u_k on the deformed source (face, barycentric b) and pulls that
// point by delta = (1 - alpha)(q - p) + alpha ((q - p) . n) n. The exact term W |sum_k b_k u_k - p - delta|^2
// couples the face's corners; it is spread over them as W b_k |u_k - (u_k + delta)|^2 (same gradient at
// the current iterate), so that every pull is a pull of a vertex and the solver's soft constraints keep one
// structure (all vertices) for the whole registration: only weights and targets change.
//
// Rejection: a correspondence farther than reject_distance times the median distance of the round, or
// whose normals make an angle over reject_angle (up to sign for unoriented, PCA-estimated normals), gets
// weight 0. Robust weights on the kept ones: Welsch, exp(-d^2 / (2 sigma^2)), sigma = robust_scale times
// their median distance (floored at floor_distance so exact data keeps weight 1).
#pragma once
#include "iarap/registration/closest_surface_point.h"
#include "iarap/registration/registration_target.h"

#include <Eigen/Core>

namespace iarap::registration_detail {

struct CorrespondenceRules {
  double point_to_plane = 0.95;
  double reject_distance = 3.0;
  double cos_reject_angle = 0.5;
  double robust_scale = 2.0;
  double floor_distance = 0; // distances below count as 0 (mesh units; e.g. 1e-12 of the diagonal)
};

// Pulls of the source vertices: weight (>= 0, 0 for none) and target per vertex.
struct VertexPulls {
  Eigen::VectorXd weight;                        // #V
  Eigen::MatrixXd target;                        // #V x 3 (the vertex's position where weight is 0)
  Eigen::Index used = 0;                         // correspondences kept
  double mean_distance = 0, median_distance = 0; // over all correspondences, before rejection
};

// The closest target point of each row of U (#U x 3): its position, unit normal and distance.
struct ClosestPoints {
  Eigen::MatrixXd position, normal; // #U x 3
  Eigen::VectorXd distance;         // #U
};
ClosestPoints closest_target_points(const Eigen::MatrixXd& U, const RegistrationTarget& target);

// The median of values (0 for none).
double median(Eigen::VectorXd values);

// Weights of correspondences at distances d with normal cosines c (#n each) by the rules above.
Eigen::VectorXd correspondence_weights(const Eigen::VectorXd& d, const Eigen::VectorXd& c, bool oriented,
                                       const CorrespondenceRules& rules);

// Source -> target pulls of the deformed source U (#V x 3) with vertex normals NU (#V x 3).
VertexPulls forward_pulls(const Eigen::MatrixXd& U, const Eigen::MatrixXd& NU,
                          const RegistrationTarget& target, const CorrespondenceRules& rules);

// Target -> source pulls on U (faces F, `around` = vertex_faces(F)), spread over the corners.
VertexPulls backward_pulls(const Eigen::MatrixXd& U, const Eigen::MatrixXd& NU, const Eigen::MatrixXi& F,
                           const VertexFaces& around, const RegistrationTarget& target,
                           const CorrespondenceRules& rules);

} // namespace iarap::registration_detail
