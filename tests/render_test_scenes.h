// What the CPU pipeline's tests share: scenes whose camera maps object coordinates straight to
// clip space, triangles given in window coordinates, and renders at a worker count or an
// instruction set. For render_test.cpp, render_raster_test.cpp and render_shading_test.cpp.
#pragma once

#include <cstdint>
#include <limits>
#include <memory>

#include <gtest/gtest.h>

#include <tessera/render/cpu_renderer.h>
#include <tessera/scene/scene.h>

namespace tessera::test {
constexpr float kInf = std::numeric_limits<float>::infinity();

// A scene whose camera maps object coordinates straight to clip space.
inline Scene clipSpaceScene() {
  Scene scene;
  scene.camera.view_override = float4x4::identity();
  scene.camera.projection_override = float4x4::identity();
  scene.ambient = float3(1.0f);
  return scene;
}

// Window coordinates (pixels, y down) and NDC depth to a clip-space position with w = 1.
inline float3 windowToNdc(float x, float y, float z, int width, int height) {
  return {2.0f * x / width - 1.0f, 1.0f - 2.0f * y / height, z};
}

inline Object unlitObject(Mesh mesh, CullMode cull = CullMode::kNone) {
  Object o;
  o.mesh = std::make_shared<Mesh>(std::move(mesh));
  o.materials[0].base_color = {1, 1, 1, 1};
  o.shading = Shading::kUnlit;
  o.cull = cull;
  return o;
}

inline Frame renderScene(const Scene& scene, int width, int height, int workers = 1,
                         PipelineStats* stats = nullptr, bool normals = false) {
  CpuRenderer renderer(workers);
  RenderOptions options;
  options.width = width;
  options.height = height;
  options.normals = normals;
  Frame frame;
  renderer.render(scene, options, frame);
  if (stats) *stats = renderer.lastStats();
  return frame;
}

// The scene rendered with the kernels of one instruction set.
inline Frame renderAt(const Scene& scene, const RenderOptions& options, SimdLevel level,
                      int workers) {
  CpuRenderer renderer(workers, level);
  Frame frame;
  renderer.render(scene, options, frame);
  return frame;
}

// One triangle given in window coordinates.
inline Mesh windowTriangle(float3 a, float3 b, float3 c, int width, int height) {
  Mesh m;
  m.positions = {windowToNdc(a.x, a.y, a.z, width, height),
                 windowToNdc(b.x, b.y, b.z, width, height),
                 windowToNdc(c.x, c.y, c.z, width, height)};
  m.indices = {0, 1, 2};
  return m;
}

inline int coveredCount(const Frame& f) {
  int n = 0;
  for (uint32_t id : f.triangle_id) n += id != kNoTriangle;
  return n;
}

// Eight pixels of several triangles shaded alike take one evaluation for the eight
// (mixed_lanes.h); with the normal AOV on, every triangle is shaded on its own. Renders `scene`
// both ways, tone mapping off and ACES, at 1 and 4 samples (the rest of the options `base`'s), and
// expects the same colours; most of the frame must be covered.
inline void expectMixedShadingMatchesPerTriangle(Scene scene, const RenderOptions& base) {
  for (ToneMapping tone : {ToneMapping::kNone, ToneMapping::kAces}) {
    scene.tone_mapping = tone;
    for (int msaa : {1, 4}) {
      RenderOptions options = base;
      options.msaa = msaa;
      options.normals = false;
      const Frame together = renderAt(scene, options, SimdLevel::kAuto, 2);
      options.normals = true;
      const Frame apart = renderAt(scene, options, SimdLevel::kAuto, 2);
      EXPECT_GT(coveredCount(together), options.width * options.height / 2);
      EXPECT_EQ(together.color, apart.color)
          << "tone mapping " << static_cast<int>(tone) << ", msaa " << msaa;
    }
  }
}

}  // namespace tessera::test
