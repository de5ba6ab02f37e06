// The free rows of the system matrix L (of L + Q with soft constraints) in the elements' visit order, as
// the streamed passes of LocalGlobalProblem read them (the fused right-hand side and gradient, the Hessian
// product). They depend on the data and its constrained set only, not on the targets: built once and kept
// in ArapData::free_rows, which arap_set_fixed and arap_set_soft_weights (commit_layout) clear. Building
// them was a sixth of a drag update on the beetle (issue 48): every update is a new solve. Internal.
#pragma once
#include "iarap/solver/arap_types.h"

#include <memory>
#include <vector>

namespace iarap::detail {

struct FreeRowSystem {
  std::vector<int> position; // #cells: the visit position of each cell (vertex)
  // Row r of the flat CSR belongs to the free vertex at visit position free_position[r] (increasing),
  // data.free(free_index[r]); its columns are visit positions.
  std::vector<int> free_position, free_index, row_start, column;
  std::vector<double> value;
};

// data.free_rows, built first when it is empty (or was built for another system matrix or free set).
std::shared_ptr<const FreeRowSystem> free_row_system(ArapData& data);

} // namespace iarap::detail
