// The clip-space scenes of the anti-aliasing tests (msaa_test.cpp, composite_test.cpp): object
// coordinates are clip coordinates, vertices given in sub-pixels, unlit white meshes.
#pragma once

#include <cstdint>
#include <memory>
#include <utility>

#include <tessera/render/cpu_renderer.h>
#include <tessera/scene/scene.h>

#include "render_test_scenes.h"

namespace tessera::test {

// Object coordinates are clip coordinates (clipSpaceScene, render_test_scenes.h), given as window
// positions in 1/256 pixel: on a power-of-two viewport every such position maps back to itself
// exactly, so the test knows the snapped vertices.
struct SubPixel {
  int64_t x, y;  // 1/256 pixel, y down
};

inline float3 toNdc(SubPixel p, float z, int width, int height) {
  const float x = static_cast<float>(p.x) / 256.0f, y = static_cast<float>(p.y) / 256.0f;
  return {2.0f * x / static_cast<float>(width) - 1.0f, 1.0f - 2.0f * y / static_cast<float>(height),
          z};
}

inline Object unlitMesh(Mesh mesh) {
  Object o;
  o.mesh = std::make_shared<Mesh>(std::move(mesh));
  o.materials[0].base_color = {1, 1, 1, 1};
  o.shading = Shading::kUnlit;
  o.cull = CullMode::kNone;
  return o;
}

inline RenderOptions optionsFor(int width, int height, int msaa) {
  RenderOptions options;
  options.width = width;
  options.height = height;
  options.msaa = msaa;
  options.coverage = true;
  return options;
}

inline Frame render(const Scene& scene, const RenderOptions& options, int workers = 1,
                    SimdLevel simd = SimdLevel::kAuto) {
  CpuRenderer renderer(workers, simd);
  Frame frame;
  renderer.render(scene, options, frame);
  return frame;
}

}  // namespace tessera::test
