// Per-frame render options.
#pragma once

#include <tessera/render/projection.h>
#include <tessera/render/sampling.h>

namespace tessera {

// How a pixel's triangle is chosen. kDepthBuffer: the nearest (the z-buffer). kPainter: the
// painter's algorithm, without a depth test: triangles sorted back to front by the average of
// their three window depths (ties in submission order) and drawn in that order, the last to
// cover a pixel keeping it; the depth AOV is then that triangle's depth. CPU backend and
// perspective projection only.
enum class Visibility { kDepthBuffer, kPainter };

// Every polygon's outline (Mesh::triangle_edges), drawn in the line pass over the image,
// depth-tested with a bias (render/line_pass.h) and anti-aliased with MSAA as lines are.
// CPU backend and perspective projection only.
struct EdgeOptions {
  bool show = false;
  float3 color{0.0f, 0.0f, 0.0f};  // linear RGB
  float width = 1.0f;              // pixels, above 0
};

// How Scene::points are drawn by the point pass (render/point_pass.h), after the triangles,
// depth-tested against them and writing depth.
struct PointOptions {
  float size = 3.0f;               // pixels across, above 0 (`--point-size`)
  bool sprites = false;            // shaded spheres instead of flat discs (`--point-sprites`)
  float3 color{1.0f, 1.0f, 1.0f};  // linear RGB, for points without colours of their own
};

// Shadow maps for directional and spot lights (render/shadow_map.h), read by per-pixel shading
// (Shading::kPhong and kPbr); flat and Gouraud surfaces and point lights stay unshadowed. CPU
// backend only (`--shadows`). Biases are in texels of the map the receiver falls in.
struct ShadowOptions {
  bool enabled = false;
  int map_size = 2048;         // texels across each map (each cascade of a directional light)
  float constant_bias = 0.5f;  // depth of this many texels at 45 degrees
  float slope_bias = 1.5f;     // times the caster's depth slope per texel (clamped to 4 texels)
  float normal_offset = 1.0f;  // the receiver moved along its normal by this many texels
};

struct RenderOptions {
  int width = 480;
  int height = 480;
  bool depth = true;      // fill Frame::depth (the depth AOV)
  bool ids = true;        // fill Frame::triangle_id (the id AOV)
  bool normals = false;   // fill Frame::normal (the normal AOV)
  bool lines = true;      // draw Scene::lines and the axes the scene asks for (needs depth: a frame
                          // that draws lines has a depth buffer whatever `depth` says)
  bool coverage = false;  // fill Frame::coverage (samples covered / samples, 0..255)
  // Fill Frame::diagnostics (diagnostics.h) in a pass of its own after the tile stage; the
  // frame then also has the depth and id AOVs, which that pass reads.
  bool diagnostics = false;
  // Samples per pixel: 1, 2, 4 or 8 (isSampleCount), at the standard positions (sampling.h).
  // Colour is resolved from every sample; depth, ids and normals stay those of the pixel centre,
  // the same as with one sample.
  int msaa = 1;
  // The sample pattern's sub-pixel offset for this frame (jitterOffset), in pixels.
  Jitter jitter;
  // How pixels map to view rays (projection.h). Perspective takes the classic pipeline; the
  // other modes test each pixel's ray against the triangles (render/ray_setup.h), with the
  // camera's fov_y_degrees as the mode's view angle.
  Projection projection = Projection::kPerspective;
  Visibility visibility = Visibility::kDepthBuffer;
  EdgeOptions edges;  // drawn when `lines` is set too
  PointOptions points;
  float line_width = 1.0f;  // Scene::lines, in pixels (`--line-width`)
  // The triangles' opacity over the background, 0..1 (`--opacity`; compositeOverBackground in
  // composite.h): only the nearest surface is seen, mixed with the background.
  float opacity = 1.0f;
  // Test objects with clusters (Object::clusters) and their clusters against the frustum (and
  // back faces by normal cones) before their vertices are transformed (perspective only). Never
  // changes the image; off for tests that compare with and without.
  bool frustum_cull = true;
  ShadowOptions shadows;
  // The caller's promise that the frame it passes holds what this renderer's last render() left
  // in it: nothing wrote to its buffers since (the frames of a sequence rendered into one Frame
  // and only read between renders). The CPU renderer then leaves the tiles that were background
  // in both renders as they are instead of filling them again, with the same image (the fill of a
  // 3840x2160 frame's background: up to 33 MB of stores). Other backends write every pixel.
  bool frame_kept = false;
};

// The options a backend renders `options` with: the diagnostics read the frame's centre depths
// and ids, so a frame that asks for them has those AOVs too.
inline RenderOptions withDiagnosticInputs(const RenderOptions& options) {
  RenderOptions measured = options;
  if (measured.diagnostics) measured.depth = measured.ids = true;
  return measured;
}

}  // namespace tessera
