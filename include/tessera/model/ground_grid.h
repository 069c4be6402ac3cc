// `--grid`: a ground grid under the model, as f3d draws one: lines on the plane perpendicular to
// the up axis through the model's lowest point, drawn by the line pass (depth-tested, behind the
// model where the model is in front).
#pragma once

#include <tessera/scene/mesh.h>
#include <tessera/scene/scene.h>

namespace tessera::model {

// The grid's cell: a power of ten, or half of one, giving between 6 and 60 cells across the
// grid (about three times the bounds' radius): 0.5 for a model of radius 1 to 9.9.
float gridUnit(const Bounds& bounds);

// Appends the grid for a model with these world bounds and this up axis (a unit world axis, as
// --up gives) to `lines`: square, centred under the bounds' centre snapped to the unit (so that
// its lines pass through the world origin's), about 1.5 radii each way, a hair below the lowest
// point so that faces lying on the ground do not hide it. Nothing for empty bounds.
void appendGroundGrid(const Bounds& bounds, float3 up, LineList& lines);

}  // namespace tessera::model
