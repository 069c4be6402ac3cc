#include "render/shade.h"

#include <algorithm>

namespace tessera::render {

float3 shadePixel(const ShadeTriangle& t, const Scene& scene, float x, float y, float3* normal) {
  // Perspective-correct barycentrics from the 1/w-weighted planes.
  const float dx = x - t.x0, dy = y - t.y0;
  const float inv_s = 1.0f / (t.inv_w0 + t.sdx * dx + t.sdy * dy);
  const float b1 = (t.p1dx * dx + t.p1dy * dy) * inv_s;
  const float b2 = (t.p2dx * dx + t.p2dy * dy) * inv_s;
  const float b0 = 1.0f - b1 - b2;

  float3 color = t.color[0] * b0 + t.color[1] * b1 + t.color[2] * b2;
  if (t.has_uv) {
    const float2 uv = t.uv[0] * b0 + t.uv[1] * b1 + t.uv[2] * b2;
    color = color * t.material->albedo->sample(uv, t.material->sampler).xyz();
  }
  if (t.shading == Shading::kPhong || (normal && t.shading != Shading::kFlat)) {
    const float3 n = normalize(t.normal[0] * b0 + t.normal[1] * b1 + t.normal[2] * b2);
    if (t.shading == Shading::kPhong) color = color * irradiance(scene, n);
    if (normal) *normal = n;
  } else if (normal) {
    *normal = t.normal[0];
  }
  return color;
}

void shadeTile(const TileVisibility& tile, int tile_index, const std::vector<TriangleChunk>& chunks,
               size_t chunk_count, const Scene& scene, bool want_normals, ShadedTile& out) {
  const int tile_x1 = tile.x0 + tile.width - 1, tile_y1 = tile.y0 + tile.height - 1;
  for (size_t c = 0; c < chunk_count; ++c) {
    const TriangleChunk& chunk = chunks[c];
    const uint32_t* end = chunk.bins.end(tile_index);
    for (const uint32_t* it = chunk.bins.begin(tile_index); it != end; ++it) {
      // The records are large and far apart: ask for the next one while this one is shaded.
      if (it + 1 != end) __builtin_prefetch(&chunk.shade[it[1]]);
      const RasterTriangle& r = chunk.raster[*it];
      const uint32_t key = makeKey(static_cast<uint32_t>(c), *it);
      const int x0 = std::max(r.min_x, tile.x0), x1 = std::min(r.max_x, tile_x1);
      const int y0 = std::max(r.min_y, tile.y0), y1 = std::min(r.max_y, tile_y1);
      const ShadeTriangle* triangle = nullptr;
      for (int y = y0; y <= y1; ++y) {
        const int row = (y - tile.y0) * kTileSize - tile.x0;
        for (int x = x0; x <= x1; ++x) {
          if (tile.key[row + x] != key) continue;
          if (!triangle) triangle = &chunk.shade[*it];
          out.color[row + x] =
              shadePixel(*triangle, scene, static_cast<float>(x) + 0.5f,
                         static_cast<float>(y) + 0.5f, want_normals ? &out.normal[row + x] : nullptr);
          out.triangle_id[row + x] = triangle->triangle_id + 1;
        }
      }
    }
  }
}

}  // namespace tessera::render
