// The line pass, after the tile stage: the scene's line lists and axes, then the polygon edges
// (RenderOptions::edges, from Mesh::triangle_edges) with a depth bias so that the edges of
// visible faces show and those of hidden ones do not. Both through lines.h.
#pragma once

#include <cstdint>
#include <vector>

#include <tessera/render/frame.h>
#include <tessera/render/options.h>
#include <tessera/scene/scene.h>

#include "render/vertex.h"

namespace tessera::render {

// The edges' depth bias: each point is pulled towards the eye by this fraction of its distance
// (LineStyle::pull). A face's own edges then pass its depth test, with room for the half-pixel
// between a line point and the pixel centre on faces up to a steep slant, while a face more
// than 0.2% of the distance behind another keeps its edges hidden.
constexpr float kEdgeDepthPull = 1.0f / 512.0f;

class EdgeLines {
 public:
  // Replaces `lines` with the outline edges of every object's mesh in world space, in `color`
  // (linear). An edge that triangles of one object share (their ends at the same positions) is
  // listed once, so an anti-aliased edge is not blended twice. The order is fixed (by the ends'
  // first vertex numbers). The buffers only grow: a frame after warm-up allocates nothing.
  void build(const Scene& scene, const std::vector<ObjectTransforms>& objects, float3 color,
             LineList& lines);

 private:
  // edges_: the mesh's outline edges as (low vertex << 32 | high vertex), of the first vertex
  // at each position, sorted and each once.
  void collect(const Mesh& mesh);

  std::vector<uint32_t> by_position_;  // vertex numbers sorted by position
  std::vector<uint32_t> canonical_;    // per vertex: the first vertex at its position
  std::vector<uint64_t> edges_;
};

// Replaces `lines` with the world axes and the axes of the objects that ask for them
// (objects[i].model: object i's frame). The scene's own lines are drawn apart, at
// RenderOptions::line_width.
void axisLines(const Scene& scene, const std::vector<ObjectTransforms>& objects, LineList& lines);

class LinePass {
 public:
  // Whether the frame has lines to draw (and so needs a depth buffer).
  static bool wanted(const Scene& scene, const RenderOptions& options);
  // Draws them over the frame (depth-tested, not depth-written); `antialiased` with MSAA.
  void draw(const Scene& scene, const std::vector<ObjectTransforms>& objects,
            const RenderOptions& options, const float4x4& view_projection, bool antialiased,
            Frame& frame);

 private:
  LineList axes_, edge_lines_;  // reused frame after frame
  EdgeLines edges_;
};

}  // namespace tessera::render
