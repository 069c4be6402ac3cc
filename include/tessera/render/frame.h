// A rendered frame: sRGB colour and the per-pixel AOVs (triangle id, window depth, world normal).
#pragma once

#include <cstdint>
#include <vector>

#include <tessera/math/vec.h>
#include <tessera/render/diagnostics.h>

namespace tessera {

constexpr uint32_t kNoTriangle = 0;

struct Frame {
  int width = 0;
  int height = 0;
  std::vector<uint32_t> color;  // RGBA8 sRGB, R in the low byte, row 0 at the top
  // The AOVs: each is empty unless RenderOptions asked for it.
  std::vector<float> depth;           // window z in [0, 1]; +inf where nothing was drawn
  std::vector<uint32_t> triangle_id;  // scene triangle index + 1; kNoTriangle where none
  std::vector<float3> normal;         // world shading normal (unit); zero where none
  // Samples covered / samples, as 0..255 (round to nearest): an alpha matte. 255 everywhere a
  // triangle covers the whole pixel; with one sample, 255 where the centre is covered.
  std::vector<uint8_t> coverage;
  // Overdraw, occupancy, material, density, tile occlusion and edges, counters and stage times:
  // valid only when RenderOptions::diagnostics asked for them.
  FrameDiagnostics diagnostics;

  // Sizes the colour buffer and the AOVs asked for to w x h and empties the others; keeps the
  // memory of a buffer whose size is unchanged (no allocation).
  void resize(int w, int h, bool with_depth, bool with_ids, bool with_normals,
              bool with_coverage = false);
  size_t pixelCount() const { return static_cast<size_t>(width) * static_cast<size_t>(height); }
  uint32_t colorAt(int x, int y) const { return color[static_cast<size_t>(y) * width + x]; }
  uint32_t idAt(int x, int y) const { return triangle_id[static_cast<size_t>(y) * width + x]; }
  float depthAt(int x, int y) const { return depth[static_cast<size_t>(y) * width + x]; }
  uint8_t coverageAt(int x, int y) const { return coverage[static_cast<size_t>(y) * width + x]; }
};

}  // namespace tessera
