// The compute backend's transparent pass (alphaMode BLEND; the CPU's blend.h and blend_kernel.h),
// compiled as shade.comp's main() with TESSERA_BLEND_PASS=1 so that a blended pixel is shaded by
// the same code as an opaque one. It runs after shading, over the output it wrote.
//
// The host orders the blended records back to front as the CPU does (vulkan/blend_order.h) and
// bins them to the 16x16 tiles in that order (binding 0 of set 1: tile t's keys are
// words[words[t] .. words[t + 1]), the offsets counted from the start of the buffer). Each
// invocation owns one pixel and walks its tile's list in order, so the result does not depend on
// scheduling: for each record, the samples it covers (the 64-bit edge functions at each visibility
// layer's point) in front of the opaque depth there (the depth plane formed as the CPU's
// blendedSamples forms it; depth is tested, never written) take the record's colour, shaded at
// the pixel centre, with its alpha (base colour alpha times the albedo texture's, as MASK reads
// it) by the over operator in linear light: C A + D (1 - A). Every sample starts at the pixel's
// resolved colour decoded from its sRGB byte (as the CPU's BlendTile), and at the end the samples
// are averaged and encoded once; the coverage AOV becomes A + c (1 - A) the same way.

layout(std430, set = 1, binding = 0) readonly buffer BlendListBuffer { uint blend_words[]; };

// The samples of pixel (x, y) that record `slot` covers in front of the opaque depth: bit s for
// sample s (visibility layer first_sample_layer + s).
uint blendedSamples(uint slot, uint pixel, int x, int y) {
  uint mask = 0u;
  const RasterRecord r = raster_records[slot];
  for (uint i = 0u; i < frame.samples; ++i) {
    const uint layer = frame.first_sample_layer + i;
    if (!layerCovered(r, x, y, layer)) continue;
    const float z = layerRecordDepth(r, x, y, layer);
    const bool empty = layerKey(pixel, layer) == kEmptyWord;
    if (empty || z < depthFromOrdered(layerDepth(pixel, layer))) mask |= 1u << i;
  }
  return mask;
}

// The record's alpha at the pixel centre (the CPU's maskedAlpha), clamped to [0, 1]; NaN is 0.
float blendAlpha(uint slot, ivec2 pixel) {
  const ShadeRecord s = shade_records[slot];
  float alpha = materials[s.material].base_color.w;
  if ((s.shading & kShadeHasUv) != 0u) {
    const vec3 b = pointBarycentrics(slot, s, pixel, kCentre);
    alpha = alpha * sampleAlbedoRgba(slot, s, b, pixel, kCentre).w;
  }
  return alpha > 0.0 ? (alpha < 1.0 ? alpha : 1.0) : 0.0;
}

void main() {
  const int x = int(gl_GlobalInvocationID.x), y = int(gl_GlobalInvocationID.y);
  if (x >= frame.width || y >= frame.height) return;
  const uint tile = uint(y >> kTileSizeLog2) * uint(frame.tile_columns) + uint(x >> kTileSizeLog2);
  const uint begin = blend_words[tile], end = blend_words[tile + 1u];
  const uint n = uint(frame.width) * uint(frame.height);
  const uint pixel = uint(y) * uint(frame.width) + uint(x);
  const bool coverage_aov = (frame.flags & kFrameCoverage) != 0u;
  const uint coverage_at = ((frame.flags & kFrameNormals) != 0u ? 6u : 3u) * n + pixel;
  const uint start = output_words[pixel];
  const vec3 behind = vec3(decodeSrgb8(start & 255u), decodeSrgb8((start >> 8) & 255u),
                           decodeSrgb8((start >> 16) & 255u));
  const float covered = coverage_aov ? float(output_words[coverage_at]) / 255.0 : 1.0;
  vec3 colors[kMaxSamples];
  float coverages[kMaxSamples];
  for (uint i = 0u; i < frame.samples; ++i) {
    colors[i] = behind;
    coverages[i] = covered;
  }
  bool touched = false;
  for (uint e = begin; e < end; ++e) {
    const uint slot = recordSlot(blend_words[e]);
    const uint mask = blendedSamples(slot, pixel, x, y);
    if (mask == 0u) continue;
    touched = true;
    const vec3 color = shadeAt(slot, ivec2(x, y), kCentre);
    const float a = blendAlpha(slot, ivec2(x, y));
    precise float keep = 1.0 - a;
    precise vec3 rgb = color * a;
    for (uint i = 0u; i < frame.samples; ++i) {
      if ((mask >> i & 1u) == 0u) continue;
      precise vec3 over = rgb + colors[i] * keep;
      precise float c = a + coverages[i] * keep;
      colors[i] = over;
      coverages[i] = c;
    }
  }
  if (!touched) return;
  precise vec3 sum = vec3(0.0);
  precise float covered_sum = 0.0;
  for (uint i = 0u; i < frame.samples; ++i) {
    sum = sum + colors[i];
    covered_sum = covered_sum + coverages[i];
  }
  const float inv = 1.0 / float(frame.samples);  // a power of two: exact
  precise vec3 average = sum * inv;
  output_words[pixel] = (start & 0xff000000u) | encodeSrgb8(average.r) |
                        (encodeSrgb8(average.g) << 8) | (encodeSrgb8(average.b) << 16);
  if (coverage_aov) {
    precise float c = clamp(covered_sum * inv, 0.0, 1.0) * 255.0;
    output_words[coverage_at] = uint(floor(c + 0.5));
  }
}
