// The line pass: world and object axes and the scene's line lists, drawn after the triangles,
// depth-tested against them but not writing depth.
#pragma once

#include <tessera/math/math.h>
#include <tessera/render/frame.h>
#include <tessera/render/projection.h>
#include <tessera/scene/scene.h>

namespace tessera::render {

// `color` (linear RGB) over the packed sRGB pixel `under` with weight `a` (0..1), in linear light:
// the colour mixed, and the alpha `a` over under's (so a line over a transparent background shows).
uint32_t blendOver(uint32_t under, float3 color, float a);

// Appends the X (red), Y (green) and Z (blue) axes of `frame_matrix` from its origin, each
// `length` long in the frame's own units.
void appendAxes(LineList& lines, const float4x4& frame_matrix, float length);

// How drawLines draws its segments.
struct LineStyle {
  // In pixels, across the line's major axis. Above one the pixels whose centres are within
  // width / 2 of the line (anti-aliased: every pixel the width overlaps, by how much).
  float width = 1.0f;
  // A depth bias that scales with distance: each point is moved this fraction of the way to
  // `eye` (world space) before projection, so it lands on the same pixel at a nearer depth.
  float pull = 0.0f;
  float3 eye{};
};

// Draws each segment (clipped to the view frustum) where it is nearer than the frame's depth.
// Antialiased (with MSAA), each step along the line's major axis covers the two pixels nearest
// it across, weighted by distance and blended in linear light.
void drawLines(const LineList& lines, const float4x4& view_projection, Frame& frame,
               bool antialiased = false, const LineStyle& style = {});

// The nonlinear projections' lines: camera-space points through the mode's mapping, depth as the
// distance from near (0) to far (1), as the ray path writes it.
struct RayLines {
  Projection projection = Projection::kSpherical;
  double fov_y_radians = 1;
  double near = 0.1, far = 100;
};
// `width` in pixels, as LineStyle::width.
void drawRayLines(const LineList& lines, const float4x4& view, const RayLines& mode, Frame& frame,
                  bool antialiased = false, float width = 1.0f);

}  // namespace tessera::render
