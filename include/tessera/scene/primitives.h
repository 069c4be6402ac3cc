// Procedural meshes.
#pragma once

#include <tessera/scene/mesh.h>

namespace tessera {

// Unit cube centred at the origin (side 1), 24 vertices with per-face normals and UVs,
// 12 counter-clockwise triangles.
Mesh makeCube();

// UV sphere of radius 1 with smooth normals and UVs. segments >= 3 around, rings >= 2 from pole
// to pole.
Mesh makeUvSphere(int segments, int rings);

}  // namespace tessera
