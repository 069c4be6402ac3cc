// Shadow maps (RenderOptions::shadows): depth maps of the scene seen from its directional and spot
// lights, rendered once per frame before the tile stage and read by the per-pixel shading (Phong
// and PBR pixels, shade_lanes.h) through LightRig::shadows.
//
// - A directional light gets kCascades orthographic maps over the view's depth range, split by a
//   mix of the logarithmic and uniform schemes (GPU Gems 3, ch. 10 "Parallel-Split Shadow Maps"),
//   each fitted to the bounding sphere of its slice of the view frustum and moved in whole texels
//   so that its texels stay put on the ground as the camera turns (no shimmer). In the nonlinear
//   projections (which see around the camera) a cascade is a sphere around the eye instead, and
//   chosen by distance rather than view depth.
// - A spot light gets one perspective map over its outer cone.
// - Point lights stay unshadowed.
//
// Bias: the map stores each caster's depth plus a slope-scaled offset, clamped (glPolygonOffset's
// form, in units of one texel's depth at 45 degrees), and a lookup moves the receiver along its
// normal by a fraction of a texel (normal-offset shadows, Holbein 2011). Filter: percentage-closer
// filtering over 3x3 texels, bilinearly weighted (a 4x4 footprint), so edges move smoothly.
//
// Deterministic by construction: each map is rasterized whole by one worker in submission order,
// and the lookup (this file's .cpp, compiled once, not per instruction set) is plain scalar float
// code, so the images are the same bits for any worker count and SIMD level.
#pragma once

#include <vector>

#include <tessera/math/vec.h>
#include <tessera/render/options.h>
#include <tessera/scene/scene.h>

namespace tessera::render {

class WorkerPool;
struct LightRig;

// One depth map and the projection into it. Light space: lx, ly, ld are p - origin along right,
// up and forward (the way the light travels). Map coordinates are in texels, (0, 0) the top-left
// corner; depth is window z in [0, 1], 0 nearest the light.
struct ShadowView {
  bool perspective = false;
  float3 origin{0, 0, 0}, right{1, 0, 0}, up{0, 1, 0}, forward{0, 0, -1};
  float cx = 0, cy = 0;    // orthographic: the map's centre in light space
  float scale = 1;         // texels per light-space unit (orthographic) or per unit of lx / ld
  float z_a = 0, z_b = 1;  // depth: (ld - z_a) * z_b (orthographic); z_a - z_b / ld (perspective)
  float near_d = 0;        // perspective: the near plane's ld
  float texel_world = 1;   // a texel's size in world units (perspective: per unit of ld)
  float reach = 0;         // a cascade serves view depths (or distances) up to this
  int size = 0;
  std::vector<float> depth;  // size * size, +inf where nothing is
  // Every object's vertices, objects one after another: light space (perspective maps) or
  // map coordinates (orthographic ones).
  std::vector<float3> light_space;

  // p in map coordinates (u, v in texels, z window depth); false behind a perspective map's near
  // plane.
  bool project(float3 p, float3& out) const;
};

class ShadowMaps {
 public:
  static constexpr int kCascades = 3;

  // Renders the maps of every directional and spot light of `rig` (prepared for `scene`) and
  // points the rig at them (LightRig::shadows, ShadeLight::shadow). `omnidirectional`: the
  // nonlinear projections' cascades, spheres around the eye. `aspect`: the image's.
  void build(const Scene& scene, const ShadowOptions& options, bool omnidirectional, float aspect,
             WorkerPool& pool, LightRig& rig);

  // How much of the light `shadow` (ShadeLight::shadow) reaches world point p with unit normal n
  // (facing the light), 0..1: exactly 1 where no filter tap is occluded. Points outside every map
  // are lit.
  float visibility(int shadow, float3 p, float3 n) const;

  int viewCount() const { return view_count_; }
  const ShadowView& view(int i) const { return views_[static_cast<size_t>(i)]; }

  // What visibility() reads besides the views, for its GPU port (src/vulkan/shadow_upload.cpp):
  // light `shadow`'s views (first, count), the eye and its forward axis (a cascade's depth is
  // along it, or the distance from the eye when omnidirectional) and the normal offset in texels.
  int lightFirstView(int shadow) const { return lights_[static_cast<size_t>(shadow)].first_view; }
  int lightViewCount(int shadow) const { return lights_[static_cast<size_t>(shadow)].view_count; }
  float3 eye() const { return eye_; }
  float3 eyeForward() const { return eye_forward_; }
  bool omnidirectional() const { return omnidirectional_; }
  float normalOffset() const { return normal_offset_; }

 private:
  struct LightMaps {
    int first_view, view_count;
  };
  void fitCascades(const Scene& scene, const Light& light, const Bounds& bounds, bool omni,
                   float aspect, int size);
  void fitSpot(const Light& light, const Bounds& bounds, int size);
  ShadowView& nextView(int size);

  std::vector<ShadowView> views_;  // reused frame to frame: only view_count_ are this frame's
  int view_count_ = 0;
  std::vector<LightMaps> lights_;
  float3 eye_{0, 0, 0}, eye_forward_{0, 0, -1};
  bool omnidirectional_ = false;
  float normal_offset_ = 1.0f;  // texels
};

// Every object's vertices into view.light_space, objects one after another; sizes the map.
void transformShadowView(const Scene& scene, ShadowView& view);
// Clears rows [row_begin, row_end) of the map and rasterizes every triangle into them (after
// transformShadowView). Bands of rows may be rendered at once, each by one worker.
void renderShadowRows(const Scene& scene, const ShadowOptions& options, int row_begin, int row_end,
                      ShadowView& view);
// Both, for the whole map.
void renderShadowView(const Scene& scene, const ShadowOptions& options, ShadowView& view);

}  // namespace tessera::render
