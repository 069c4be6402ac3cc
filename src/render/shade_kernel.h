// The shading kernel, written once against eight-lane types (simd_lanes.h) and compiled per
// instruction set (shade_<isa>.cpp). Each lane does exactly the float operations, in exactly the
// order, that shading one pixel takes, so every variant gives the same bits. Texture samples are
// taken lane by lane through the one sampleAlbedo.
#pragma once

#include <algorithm>

#include <tessera/scene/color.h>

#include "render/shade.h"
#include "render/simd_lanes.h"

namespace tessera::render {
namespace {  // one private copy per translation unit, each compiled for its instruction set

struct Vec3x8 {
  F32x8 x, y, z;
};

TESSERA_LANES_INLINE Vec3x8 interpolate(const float3 v[3], F32x8 b0, F32x8 b1, F32x8 b2) {
  return {splat(v[0].x) * b0 + splat(v[1].x) * b1 + splat(v[2].x) * b2,
          splat(v[0].y) * b0 + splat(v[1].y) * b1 + splat(v[2].y) * b2,
          splat(v[0].z) * b0 + splat(v[1].z) * b1 + splat(v[2].z) * b2};
}

// As tessera::normalize: zero for a zero vector.
TESSERA_LANES_INLINE Vec3x8 normalize8(Vec3x8 v) {
  const F32x8 len = squareRoot(v.x * v.x + v.y * v.y + v.z * v.z);
  const F32x8 inv = splat(1.0f) / len;
  const I32x8 nonzero = positive(len);
  const F32x8 zero = splat(0.0f);
  return {select(nonzero, v.x * inv, zero), select(nonzero, v.y * inv, zero),
          select(nonzero, v.z * inv, zero)};
}

// As render::irradiance: ambient plus every directional light.
TESSERA_LANES_INLINE Vec3x8 irradiance8(const Scene& scene, const Vec3x8& n) {
  Vec3x8 e{splat(scene.ambient.x), splat(scene.ambient.y), splat(scene.ambient.z)};
  const F32x8 zero = splat(0.0f);
  for (const DirectionalLight& light : scene.lights) {
    const F32x8 cos_theta =
        zero - (n.x * splat(light.direction.x) + n.y * splat(light.direction.y) +
                n.z * splat(light.direction.z));
    const I32x8 lit = positive(cos_theta);
    e.x = e.x + select(lit, splat(light.color.x) * cos_theta, zero);
    e.y = e.y + select(lit, splat(light.color.y) * cos_theta, zero);
    e.z = e.z + select(lit, splat(light.color.z) * cos_theta, zero);
  }
  return e;
}

// Eight encodeSrgb8s (tessera/scene/color.h), the same operations lane by lane.
TESSERA_LANES_INLINE I32x8 encodeSrgb8x8(F32x8 linear, const SrgbEncodeTable& table) {
  const F32x8 zero = splat(0.0f), one = splat(1.0f);
  const F32x8 c = select(positive(linear), select(lessThan(linear, one), linear, one), zero);
  const I32x8 small = lessThan(c, splat(0x1p-12f));
  const I32x8 bits = bitsOf(c);
  const I32x8 bucket =
      select(small, splat(int32_t{0}),
             shiftRight(bits - splat(static_cast<int32_t>(SrgbEncodeTable::kFirstBits)),
                        SrgbEncodeTable::kShift));
  const F32x8 t = toFloat(bits & splat(static_cast<int32_t>((1u << SrgbEncodeTable::kShift) - 1)));
  const F32x8 code = select(small, c * splat(12.92f * 255.0f),
                            gather(table.offset, bucket) + gather(table.slope, bucket) * t);
  return truncate(code + splat(0.5f));
}

template <typename V>
TESSERA_LANES_INLINE void storeMasked(void* p, I32x8 mask, V value) {
  store(p, select(mask, value, load<V>(p)));
}

// Shades the pixels of row y, columns x..x+7, that `mask` marks as owned by triangle t.
TESSERA_LANES_INLINE void shadeRow8(const ShadeTriangle& t, const Scene& scene, bool want_normals,
                                    int x, int y, I32x8 mask, int index, ShadedTile& out) {
  const F32x8 px = toFloat(splat(x) + iota()) + splat(0.5f);
  const float py = static_cast<float>(y) + 0.5f;
  // Barycentrics exactly as barycentricsAt.
  const F32x8 dx = px - splat(t.x0);
  const float dy = py - t.y0;
  const F32x8 inv_s = splat(1.0f) / (splat(t.inv_w0) + splat(t.sdx) * dx + splat(t.sdy * dy));
  const F32x8 b1 = (splat(t.p1dx) * dx + splat(t.p1dy * dy)) * inv_s;
  const F32x8 b2 = (splat(t.p2dx) * dx + splat(t.p2dy * dy)) * inv_s;
  const F32x8 b0 = splat(1.0f) - b1 - b2;

  Vec3x8 color = interpolate(t.color, b0, b1, b2);
  if (t.has_uv) {
    for (int l = 0; l < 8; ++l) {
      if (!lane(mask, l)) continue;
      const float3 a = sampleAlbedo(t, {lane(b0, l), lane(b1, l), lane(b2, l)}, lane(px, l), py);
      setLane(color.x, l, lane(color.x, l) * a.x);
      setLane(color.y, l, lane(color.y, l) * a.y);
      setLane(color.z, l, lane(color.z, l) * a.z);
    }
  }
  if (t.shading == Shading::kPhong || (want_normals && t.shading != Shading::kFlat)) {
    const Vec3x8 n = normalize8(interpolate(t.normal, b0, b1, b2));
    if (t.shading == Shading::kPhong) {
      const Vec3x8 e = irradiance8(scene, n);
      color = {color.x * e.x, color.y * e.y, color.z * e.z};
    }
    if (want_normals) {
      storeMasked(out.normal_x + index, mask, n.x);
      storeMasked(out.normal_y + index, mask, n.y);
      storeMasked(out.normal_z + index, mask, n.z);
    }
  } else if (want_normals) {
    storeMasked(out.normal_x + index, mask, splat(t.normal[0].x));
    storeMasked(out.normal_y + index, mask, splat(t.normal[0].y));
    storeMasked(out.normal_z + index, mask, splat(t.normal[0].z));
  }
  storeMasked(out.red + index, mask, color.x);
  storeMasked(out.green + index, mask, color.y);
  storeMasked(out.blue + index, mask, color.z);
  storeMasked(out.triangle_id + index, mask, splat(static_cast<int32_t>(t.triangle_id + 1)));
}

// Encodes the shaded pixels of the tile to sRGB, eight at a time; the background elsewhere.
TESSERA_LANES_INLINE void encodeTile(const TileVisibility& tile, uint32_t background,
                                     ShadedTile& out) {
  const SrgbEncodeTable& table = srgbEncodeTable();
  const I32x8 empty = splat(static_cast<int32_t>(kEmptyKey));
  const I32x8 fill = splat(static_cast<int32_t>(background));
  const I32x8 opaque = splat(static_cast<int32_t>(0xff000000u));
  for (int ty = 0; ty < tile.height; ++ty) {
    for (int tx = 0; tx < tile.width; tx += 8) {
      const int i = ty * kTileSize + tx;
      const I32x8 drawn = ~equal(load<I32x8>(tile.key + i), empty);
      if (!any(drawn)) {
        store(out.rgba + i, fill);
        continue;
      }
      const I32x8 rgba = encodeSrgb8x8(load<F32x8>(out.red + i), table) |
                         shiftLeft(encodeSrgb8x8(load<F32x8>(out.green + i), table), 8) |
                         shiftLeft(encodeSrgb8x8(load<F32x8>(out.blue + i), table), 16) | opaque;
      store(out.rgba + i, select(drawn, rgba, fill));
    }
  }
}

void shadeTileKernel(const TileVisibility& tile, const uint32_t* drawn, size_t drawn_count,
                     const std::vector<TriangleChunk>& chunks, const Scene& scene,
                     bool want_normals, uint32_t background, ShadedTile& out) {
  const int tile_x1 = tile.x0 + tile.width - 1, tile_y1 = tile.y0 + tile.height - 1;
  for (size_t i = 0; i < drawn_count; ++i) {
    const uint32_t k = drawn[i];
    const TriangleChunk& chunk = chunks[keyChunk(k)];
    // The records are large and far apart: ask for the next one while this one is shaded.
    if (i + 1 < drawn_count)
      __builtin_prefetch(&chunks[keyChunk(drawn[i + 1])].shade[keyLocal(drawn[i + 1])]);
    const RasterTriangle& r = chunk.raster[keyLocal(k)];
    const I32x8 key = splat(static_cast<int32_t>(k));
    const int x0 = std::max(r.min_x, tile.x0), x1 = std::min(r.max_x, tile_x1);
    const int y0 = std::max(r.min_y, tile.y0), y1 = std::min(r.max_y, tile_y1);
    const I32x8 last = splat(x1);
    const ShadeTriangle* triangle = nullptr;
    for (int y = y0; y <= y1; ++y) {
      const int row = (y - tile.y0) * kTileSize - tile.x0;
      for (int x = x0; x <= x1; x += 8) {
        const I32x8 mask =
            equal(load<I32x8>(tile.key + row + x), key) & lessOrEqual(splat(x) + iota(), last);
        if (!any(mask)) continue;
        if (!triangle) triangle = &chunk.shade[keyLocal(k)];
        shadeRow8(*triangle, scene, want_normals, x, y, mask, row + x, out);
      }
    }
  }
  encodeTile(tile, background, out);
}

}  // namespace
}  // namespace tessera::render
