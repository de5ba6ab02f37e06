// Carries a constraint set over to a mesh whose vertices were renumbered (e.g. by repair_mesh).
#pragma once
#include "iarap/scene/constraint_set.h"

namespace iarap {

// old_to_new(i) is the new index of old vertex i, or -1 when it was removed. Vertices merged into
// one must agree on their targets. Throws InputError naming the old vertex index when a constrained
// vertex was removed, is out of old_to_new's range, or two merged vertices get different targets.
// Soft constraints cannot be carried by a vertex map alone (their faces need remapping): throws InputError
// naming the first of them; use the overload below.
ConstraintSet remap_constraints(const ConstraintSet& constraints, const Eigen::VectorXi& old_to_new);

// Constrains every copy a split made of a hard-constrained vertex (new_to_old: the old vertex each new one
// stands for; the first copy is the smallest new index) to its target, unless the copy is constrained
// already. Appends rows (and origins) in the order of the copies.
void constrain_split_copies(ConstraintSet& constraints, const Eigen::VectorXi& new_to_old);

// What a renumbering (repair_mesh: RepairResult's maps and faces) did: enough to carry every kind of
// constraint over.
struct MeshRenumbering {
  Eigen::VectorXi old_to_new; // #V_old: new index of each old vertex (its first copy), -1 where removed
  Eigen::VectorXi new_to_old; // #V_new: the old vertex each new one stands for (copies share one)
  Eigen::MatrixXi old_F;      // #F_old x 3
  Eigen::MatrixXi new_F;      // #F_new x 3
};

// Every constraint of the set on the renumbered mesh:
// - hard vertices as above, and every copy a split made of one gets its target too;
// - a soft vertex's weight W is shared by its k copies (W / k each: the same pull where they coincide);
//   soft vertices welded into one become one, with the summed weight and the weighted mean target (the
//   same penalty up to a constant);
// - a point on a face (soft or hard) moves to the face that stands for it (the same three corners up to
//   welds and splits; a duplicate face that was dropped stands for the one kept), its barycentric
//   coordinates following the corners (reoriented faces permute them).
// Throws InputError naming the constraint's origin when its vertex or face was removed (an unreferenced
// vertex, a degenerate or collapsed face), and as the overload above.
ConstraintSet remap_constraints(const ConstraintSet& constraints, const MeshRenumbering& renumbering);

} // namespace iarap
