#include "render/resolve.h"

#include <tessera/scene/color.h>

#include "render/shade.h"

namespace tessera::render {

void resolveTile(const TileVisibility& tile, const std::vector<TriangleChunk>& chunks,
                 const Scene& scene, Frame& frame) {
  const uint32_t background = packSrgba8(scene.background);
  const bool normals = !frame.normal.empty();
  for (int ty = 0; ty < tile.height; ++ty) {
    const int y = tile.y0 + ty;
    const size_t row = static_cast<size_t>(y) * frame.width;
    for (int tx = 0; tx < tile.width; ++tx) {
      const int x = tile.x0 + tx;
      const size_t p = row + x;
      const int t = ty * kTileSize + tx;
      const uint32_t key = tile.key[t];
      if (key == kEmptyKey) {
        frame.color[p] = background;
        frame.depth[p] = tile.depth[t];
        frame.triangle_id[p] = kNoTriangle;
        if (normals) frame.normal[p] = float3{};
        continue;
      }
      const ShadeTriangle& triangle = chunks[keyChunk(key)].shade[keyLocal(key)];
      const ShadedPixel shaded =
          shadePixel(triangle, scene, static_cast<float>(x) + 0.5f, static_cast<float>(y) + 0.5f);
      frame.color[p] = packSrgba8(float4{shaded.color.xyz(), 1.0f});
      frame.depth[p] = tile.depth[t];
      frame.triangle_id[p] = triangle.triangle_id + 1;
      if (normals) frame.normal[p] = shaded.normal;
    }
  }
}

}  // namespace tessera::render
