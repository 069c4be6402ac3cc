// Tangents for normal maps, after MikkTSpace (Morten Mikkelsen, "Simulation of wrinkled surfaces
// revisited", 2008, and the description in mikktspace.h): the convention glTF 2.0 asks clients to
// use for a normal-mapped primitive without TANGENT, and the one Blender and the exporters bake
// normal maps against. Our own implementation; the rules it follows and the ones it leaves are
// listed in src/scene/tangents.cpp and docs/formats.md.
#pragma once

#include <cstddef>
#include <span>
#include <utility>

#include <tessera/scene/mesh.h>

namespace tessera {

// What generateTangents did beyond writing one tangent per vertex.
struct TangentReport {
  // Vertices added because the corners of one vertex fell in different tangent spaces (a mirrored
  // UV seam: corners of both orientations); each copies every per-vertex array of its original.
  size_t split_vertices = 0;
  // Corners with no usable UV gradient anywhere around their vertex (zero UV area, zero area,
  // non-finite data): an arbitrary unit tangent across the normal, sign +1.
  size_t fallback_corners = 0;
};

// A half-open range [first, second) of vertex indices.
using VertexRange = std::pair<size_t, size_t>;

// Per-vertex MikkTSpace tangents (Mesh::tangents: xyz unit and across the normal, w = +-1) for the
// whole mesh, from the UVs of set `uv_set` (1: Mesh::uvs1 where the mesh has it, else Mesh::uvs;
// the normal map's set). Needs normals and UVs, one per vertex (else clears tangents and does
// nothing else). May add vertices (TangentReport::split_vertices) and rewrite indices to them.
TangentReport generateTangents(Mesh& mesh, int uv_set = 0);

// The same for the triangles whose three corners lie in `ranges` (a glTF mesh's primitives
// without TANGENT); the other vertices keep their tangents (resized to (1, 0, 0, 1) if missing).
TangentReport generateTangents(Mesh& mesh, std::span<const VertexRange> ranges, int uv_set = 0);

}  // namespace tessera
