// The compute backend's MASK pass (alphaMode MASK; the CPU's rasterMasked, mask_kernel.h),
// compiled as shade.comp's main() with TESSERA_MASK_PASS=1 so that the alpha is read with the
// shading's own texture sampling. It runs after the fine raster (which setup leaves the masked
// records out of: kFrameMaskPass) and before shading, on devices with 64-bit atomics.
//
// The host bins the masked records to the 16x16 tiles (binding 0 of set 1, as blend_pass.glsl's
// list; submission order, which the commits do not depend on). One invocation per pixel walks its
// tile's list: for each record and visibility layer, where the layer's point passes the three
// 64-bit edge tests, the depth plane there (formed as the CPU forms it) and the alpha at the point
// (base colour alpha times the albedo texture's, with the colour's sampler and level of detail:
// the CPU's maskedAlpha) reaching the cutoff, it commits ordered(depth) << 32 | key with the same
// 64-bit atomicMin as the fine raster: the nearest wins, the first in submission order among
// equals, as the CPU's z < stored in submission order.

layout(std430, set = 1, binding = 0) readonly buffer MaskListBuffer { uint mask_words[]; };
layout(std430, set = 0, binding = 17) buffer VisibilityCommits { uint64_t visibility_commits[]; };

void main() {
  const int x = int(gl_GlobalInvocationID.x), y = int(gl_GlobalInvocationID.y);
  if (x >= frame.width || y >= frame.height) return;
  const uint tile = uint(y >> kTileSizeLog2) * uint(frame.tile_columns) + uint(x >> kTileSizeLog2);
  const uint begin = mask_words[tile], end = mask_words[tile + 1u];
  const uint pixel = uint(y) * uint(frame.width) + uint(x);
  for (uint e = begin; e < end; ++e) {
    const uint slot = recordSlot(mask_words[e]);
    const RasterRecord r = raster_records[slot];
    const ShadeRecord s = shade_records[slot];
    const GpuMaterial m = materials[s.material];
    for (uint layer = 0u; layer < frame.layers; ++layer) {
      if (!layerCovered(r, x, y, layer)) continue;
      const float z = layerRecordDepth(r, x, y, layer);
      float alpha = m.base_color.w;
      if ((s.shading & kShadeHasUv) != 0u) {
        const vec3 b = pointBarycentrics(slot, s, ivec2(x, y), layer);
        alpha = alpha * sampleAlbedoRgba(slot, s, b, ivec2(x, y), layer).w;
      }
      if (!(alpha >= m.uv_transform[0].w)) continue;
      atomicMin(visibility_commits[pixel * frame.layers + layer],
                (uint64_t(orderedDepth(z)) << 32) | uint64_t(r.key));
    }
  }
}
