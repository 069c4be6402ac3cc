// Scenes small enough to count diagnostics by hand, shared by the CPU's and the Vulkan
// backends' diagnostics tests (so both backends are held to the same numbers).
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <random>
#include <vector>

#include <tessera/render/diagnostics.h>
#include <tessera/scene/scene.h>

#include "render_test_scenes.h"

namespace tessera::diagnostics_test {

// A camera that maps object coordinates straight to clip space (x, y, z in NDC, w = 1).
using test::clipSpaceScene;

// An axis-aligned rectangle in window pixels (y down) at NDC depth z, as two triangles.
inline void addRect(Mesh& m, float x0, float y0, float x1, float y1, float z, int width, int height,
                    uint16_t material = 0) {
  const uint32_t base = static_cast<uint32_t>(m.positions.size());
  auto ndc = [&](float x, float y) {
    return float3{2.0f * x / width - 1.0f, 1.0f - 2.0f * y / height, z};
  };
  m.positions.insert(m.positions.end(), {ndc(x0, y0), ndc(x1, y0), ndc(x1, y1), ndc(x0, y1)});
  m.indices.insert(m.indices.end(), {base, base + 2, base + 1, base, base + 3, base + 2});
  m.triangle_materials.insert(m.triangle_materials.end(), {material, material});
}

inline Object objectOf(Mesh mesh, CullMode cull = CullMode::kNone) {
  Object o;
  o.mesh = std::make_shared<Mesh>(std::move(mesh));
  o.shading = Shading::kUnlit;
  o.cull = cull;
  return o;
}

inline void expectCountersAddUp(const PipelineCounters& c) {
  EXPECT_EQ(c.triangles_in, c.culled.total() + c.triangles_setup - c.clip_splits);
}

// `count` full-screen quads of a width x height frame, alternately near and far (so later tests
// both pass and fail), quad i at NDC z (i odd ? 0.5 : -0.5) + 0.01 i.
inline Scene stackedQuads(int count, int width, int height) {
  Scene scene = clipSpaceScene();
  Mesh m;
  for (int i = 0; i < count; ++i)
    addRect(m, 0, 0, static_cast<float>(width), static_cast<float>(height),
            (i % 2 ? 0.5f : -0.5f) + 0.01f * static_cast<float>(i), width, height);
  scene.objects.push_back(objectOf(m));
  return scene;
}

// Three rectangles and a culled back face in a 192x128 frame (3 x 2 tiles of 64): the
// occupancy is {4, 2, 0, 0, 0, 2}.
constexpr int kOccupancyWidth = 192, kOccupancyHeight = 128;
inline Scene occupancyScene() {
  constexpr int kW = kOccupancyWidth, kH = kOccupancyHeight;
  Scene scene = clipSpaceScene();
  Mesh m;
  addRect(m, 4, 4, 20, 20, 0, kW, kH);      // tile 0: 2 triangles
  addRect(m, 50, 10, 80, 30, 0, kW, kH);    // tiles 0 and 1: 2 triangles each
  addRect(m, 140, 70, 150, 90, 0, kW, kH);  // tile 5: 2 triangles
  scene.objects.push_back(objectOf(m));
  // A back-facing triangle in tile 3, culled: binned nowhere.
  Mesh back;
  addRect(back, 10, 70, 30, 90, 0, kW, kH);
  std::swap(back.indices[1], back.indices[2]);
  back.indices.resize(3);
  back.triangle_materials.resize(1);
  scene.objects.push_back(objectOf(back, CullMode::kBack));
  return scene;
}

// The diagnostics of occupancyScene() that a backend binning on the 64x64 grid gives.
inline void expectOccupancySceneCounts(const FrameDiagnostics& d) {
  ASSERT_EQ(d.tile_columns, 3);
  ASSERT_EQ(d.tile_rows, 2);
  EXPECT_EQ(d.tile_triangles, (std::vector<uint32_t>{4, 2, 0, 0, 0, 2}));
  EXPECT_EQ(d.counters.triangles_binned, 8u);
  EXPECT_EQ(d.counters.tiles_empty, 3u);
  EXPECT_EQ(d.counters.culled.facing, 1u);
  expectCountersAddUp(d.counters);
}

// One triangle for each cull reason (but invalid and clipped away), one clipped into two pieces
// and one drawn, in a 64x64 frame, the object culling back faces.
inline Mesh cullReasonMesh() {
  Mesh m;
  const float nan = std::numeric_limits<float>::quiet_NaN();
  m.positions = {{-1, -1, 0},
                 {1, -1, 0},
                 {0, 1, 0},
                 {nan, 0, 0},
                 {3, 0, 0},
                 {4, 1, 0},
                 {3, 1, 0},  // beyond the right plane
                 {-1, -1, -3},
                 {1, -1, 0.5f},
                 {0, 1, 0.5f},  // crosses the near plane
                 // window x 35.10..35.39, y 28.51..28.80: no pixel centre in its box
                 {0.097f, 0.1f, 0},
                 {0.106f, 0.1f, 0},
                 {0.097f, 0.109f, 0}};
  m.indices = {0,  1,  3,   // non-finite
               4,  5,  6,   // frustum
               0,  0,  1,   // degenerate
               0,  2,  1,   // back-facing, culled
               7,  8,  9,   // clipped into two pieces
               10, 11, 12,  // no pixel centre
               0,  1,  2};  // drawn
  return m;
}

// Triangles about a pixel in size, one about the centre c of every third pixel of a width x height
// frame, its corners within 1.45 pixels of c (so it can cover only the 3 x 3 centres about c), both
// windings. By float tests that hold whatever the snapping to 1/256 pixel (every corner at least
// 1/32 pixel from the lines of centres, every edge at least 1/32 pixel from each centre):
// `pixel[i]`, c's pixel; `covered[i]`, the pixels of the 3 x 3 whose centres triangle i covers;
// `dropped[i]`, whether setup drops it at one sample (missesEveryCentre): its box holds no
// centre, or at most two a side and none covered.
struct FewCentres {
  Scene scene;
  std::vector<std::pair<int, int>> pixel;
  std::vector<std::vector<std::pair<int, int>>> covered;
  std::vector<bool> dropped;
};
inline FewCentres fewCentreScene(int width, int height) {
  FewCentres out{clipSpaceScene(), {}, {}, {}};
  Mesh m;
  std::mt19937 rng(17);
  std::uniform_real_distribution<float> offset(-1.45f, 1.45f);
  const auto off_lines = [](float v) {  // from the centres' lines k + 0.5
    const float f = v - 0.5f - std::floor(v - 0.5f);
    return std::min(f, 1.0f - f) > 1.0f / 32.0f;
  };
  for (int py = 1; py + 1 < height; py += 3)
    for (int px = 1; px + 1 < width; px += 3) {
      const float cx = static_cast<float>(px) + 0.5f, cy = static_cast<float>(py) + 0.5f;
      float x[3], y[3];
      std::vector<std::pair<int, int>> covered;
      bool dropped = false;
      for (;;) {
        bool clear = true;
        for (int k = 0; k < 3; ++k) {
          x[k] = cx + offset(rng), y[k] = cy + offset(rng);
          clear &= off_lines(x[k]) && off_lines(y[k]);
        }
        const float area = (x[1] - x[0]) * (y[2] - y[0]) - (y[1] - y[0]) * (x[2] - x[0]);
        if (!clear || std::fabs(area) < 0.1f) continue;
        covered.clear();
        int columns = 0, rows = 0;
        for (int j = -1; j <= 1; ++j) {
          const float y_c = cy + static_cast<float>(j);
          rows += y_c > *std::min_element(y, y + 3) && y_c < *std::max_element(y, y + 3);
          for (int i = -1; i <= 1; ++i) {
            const float x_c = cx + static_cast<float>(i);
            if (j == -1)
              columns += x_c > *std::min_element(x, x + 3) && x_c < *std::max_element(x, x + 3);
            int inside = 0;
            for (int k = 0; k < 3; ++k) {
              const int n = (k + 1) % 3;
              const float ex = x[n] - x[k], ey = y[n] - y[k];
              const float cross = ex * (y_c - y[k]) - ey * (x_c - x[k]);
              clear &= std::fabs(cross) / std::hypot(ex, ey) > 1.0f / 32.0f;
              inside += (cross > 0) == (area > 0);
            }
            if (inside == 3) covered.emplace_back(px + i, py + j);
          }
        }
        if (!clear) continue;
        dropped = columns == 0 || rows == 0 || (columns <= 2 && rows <= 2 && covered.empty());
        break;
      }
      const uint32_t base = static_cast<uint32_t>(m.positions.size());
      for (int k = 0; k < 3; ++k)
        m.positions.push_back({2.0f * x[k] / static_cast<float>(width) - 1.0f,
                               1.0f - 2.0f * y[k] / static_cast<float>(height), 0.0f});
      m.indices.insert(m.indices.end(), {base, base + 1, base + 2});
      out.pixel.emplace_back(px, py);
      out.covered.push_back(covered);
      out.dropped.push_back(dropped);
    }
  out.scene.objects.push_back(objectOf(m));
  return out;
}

}  // namespace tessera::diagnostics_test
