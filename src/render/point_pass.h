// The point pass: Scene::points as discs RenderOptions::points.size pixels across (or, with
// `sprites`, as lit sphere impostors), drawn after the triangles on the resolved frame,
// depth-tested against the frame's depth and writing it, before the line pass (so points hide
// the lines behind them).
//
// Order independence: every pixel keeps the least key (window depth bits << 32 | rank + 1) of
// the points that touch it, seeded with (its depth bits << 32 | 0), so a point must be strictly
// nearer than what is there (z < stored, as the triangles test). Window depth in [0, 1] orders as
// its float bits. The rank is the point's place in the list of its band of rows, which holds its
// points in index order: of two points at one depth the lower index wins. A minimum does not
// depend on the order the points arrive in, so the image is bit-identical for any worker count.
//
// Stages, each spread over the worker pool:
//   count:  fixed blocks of points projected (projectBlock); per chunk of blocks, how many
//           points touch each band of kPointBandRows rows
//   place:  the same blocks projected again by the same code (the same bits), each visible
//           point's record written into every band it touches, chunk after chunk
//   splat:  per band: seed the keys from the depth, splat every record's disc, then resolve the
//           band's pixels (colour, depth, AOVs) from the winning records
//
// Coverage: a pixel is covered when its centre is within size / 2 of the projected point, and the
// pixel holding the point always is (a point smaller than a pixel never vanishes). Antialiased
// (MSAA), the pixels within half a pixel more get the disc's colour blended in linear light by
// their coverage, clamp(size / 2 + 0.5 - distance, 0, 1), over what the triangles left; only the
// winner blends, so a pixel takes one point's colour, whatever the order.
//
// Clipping: points nearer than near, past far, behind the eye or not finite are not drawn; a
// disc whose centre is off the image still draws its pixels on it.
//
// AOVs where a point covers the pixel centre: depth is its window depth (with sprites, that of
// the sphere's surface); the normal (when asked) the sphere's world normal with sprites, the
// camera's backward axis without (a flat disc faces the camera); the id AOV is set to kNoTriangle,
// the background's: points have no triangle index. Colour: the point's own (PointList::colors),
// else RenderOptions::points.color; flat discs are unlit like lines, sprites are lit by the scene's
// lights (lights.h irradiance).
#pragma once

#include <cstdint>
#include <vector>

#include <tessera/math/mat.h>
#include <tessera/render/frame.h>
#include <tessera/render/options.h>
#include <tessera/scene/scene.h>

#include "render/lights.h"
#include "render/lines.h"
#include "render/worker_pool.h"

namespace tessera::render {

// Rows per band: a band's keys, colours and coverage (1920 x 32 x 13 bytes, 800 KB) stay in a
// Zen 4 core's 1 MB L2; a 3-pixel point straddles two bands one time in sixteen. 16 rows were
// 5% slower on the points bench scene (twice the bands for the place stage to scatter into).
constexpr int kPointBandRows = 32;

// Pixels [first, last] along one axis; empty when first > last.
struct PixelSpan {
  int first = 1, last = 0;
  bool empty() const { return first > last; }
};

// How world points map to window points.
struct PointCamera {
  Projection projection = Projection::kPerspective;
  float4x4 view_projection;  // perspective: world to clip, jittered as the triangles'
  float4x4 view;             // world to camera
  RayLines rays;             // the nonlinear projections: their mapping, near and far

  static PointCamera perspective(const float4x4& view_projection, const float4x4& view) {
    return {Projection::kPerspective, view_projection, view, {}};
  }
};

class PointPass {
 public:
  // Whether the scene has points to draw (the frame then needs a depth buffer).
  static bool wanted(const Scene& scene) { return !scene.points.empty(); }
  // Draws them over `frame`, which has a depth buffer. `antialiased`: with MSAA. The buffers
  // only grow: a frame after warm-up allocates nothing.
  void draw(const Scene& scene, const RenderOptions& options, const PointCamera& camera,
            bool antialiased, WorkerPool& pool, Frame& frame);

  // A point's place in its band: window position, depth bits, and its index in the PointList.
  struct Record {
    float x, y;
    uint32_t depth;
    uint32_t index;
  };

 private:
  void countChunk(size_t chunk);
  void placeChunk(size_t chunk);
  void splatBand(int band, Frame& frame);
  void resolveBand(int band, Frame& frame);
  // Flat discs without antialiasing (the common case): pixels rows x cols of the disc about
  // (x, y).
  void splatFlat(PixelSpan rows, PixelSpan cols, float x, float y, uint64_t key, uint32_t color);
  uint8_t coverageByte(bool centre, float d2) const;
  // A sprite's lit colour at pixel (px, py) and its world normal there.
  float3 spriteColor(const Record& rec, int px, int py, float3& normal) const;
  // `coverage` 255: the colour; less: blended over the frame's in linear light.
  static void writePixel(Frame& frame, size_t i, float3 color, uint8_t coverage);

  // This frame's inputs.
  const Scene* scene_ = nullptr;
  const RenderOptions* options_ = nullptr;
  PointCamera camera_;
  bool antialiased_ = false;
  int width_ = 0, height_ = 0, bands_ = 0;
  float radius_ = 0;  // in pixels
  LightRig lights_;
  float3x3 camera_to_world_;  // rotation: sprite normals from camera to world space

  std::vector<uint32_t> counts_;    // [chunk * bands_ + band]: then where the chunk's records start
  std::vector<size_t> band_start_;  // bands_ + 1 entries
  std::vector<Record> records_;
  std::vector<uint32_t> record_colors_;  // beside records_: the point's colour, packed sRGB
  // Per pixel: the least key, and that point's packed colour and coverage (255: whole).
  std::vector<uint64_t> keys_;
  std::vector<uint32_t> win_color_;
  std::vector<uint8_t> win_coverage_;
};

}  // namespace tessera::render
