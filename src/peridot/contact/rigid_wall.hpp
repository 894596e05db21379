#pragma once
// The symmetry check of rigid walls. A wall (the deck's rigid_walls) is a rigid plane among the rigid bodies
// (rigid_body.hpp), penalty contact on every point behind it, moving along its normal at its speed. A wall
// with `contact: symmetry` is, besides, a symmetry plane for the correspondence points near it
// (correspondence/mirror_bonds.hpp): they are bonded to the mirror images of their neighbours from t = 0
// until the body leaves; its force in the history then adds what those bonds exert.
#include <vector>

#include "peridot/deck/problem.hpp"
#include "peridot/materials/model_context.hpp"
#include "peridot/state/fields.hpp"

namespace peridot {

/// Refuses (InputError at the wall) a wall with contact: symmetry that the mirror bonds cannot model, from
/// the whole problem's points `disc` and the blocks' `params`: with a point of a non-correspondence body
/// within that body's horizon of it; with a
/// point behind it at t = 0; when no correspondence point is within a horizon of it, or the nearest is not
/// half its spacing (V^(1/3)/2, within 2 %) from it, so that the body's surface is not on the plane and
/// the images would overlap the body or leave a gap; with a point within a horizon of two such walls.
void check_symmetry_walls(const Problem& problem, const Discretization& disc, const std::vector<MaterialParams>& params);

}  // namespace peridot
