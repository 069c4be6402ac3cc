// Sampling: the standard multisample positions, the sub-pixel jitter sequence, and the jitter's
// projection. Every backend takes its sample positions and jitter from here, so that coverage is
// the same bits on each. Header-only.
#pragma once

#include <cstdint>
#include <span>

#include <tessera/math/mat.h>

namespace tessera {

// A sample position inside its pixel, in 1/256 pixel from the pixel's top-left corner (y down):
// the 8-bit sub-pixel grid the edge functions use (render/fixed_point.h).
struct SamplePosition {
  int32_t x, y;
};

// Vulkan's standardSampleLocations (the same as Direct3D's standard patterns), in 1/16 pixel
// units times 16. Each pattern is listed nearest the pixel centre first (ties in the order of the
// specification): shading takes the first covered sample when the centre is outside a triangle.
inline constexpr SamplePosition kSamples1[] = {{128, 128}};
inline constexpr SamplePosition kSamples2[] = {{192, 192}, {64, 64}};
inline constexpr SamplePosition kSamples4[] = {{96, 32}, {224, 96}, {32, 160}, {160, 224}};
inline constexpr SamplePosition kSamples8[] = {{144, 80}, {112, 176}, {208, 144}, {80, 48},
                                               {48, 208}, {16, 112},  {176, 240}, {240, 16}};

inline constexpr int kMaxSamples = 8;

// 1, 2, 4 and 8 samples per pixel.
constexpr bool isSampleCount(int n) {
  return n == 1 || n == 2 || n == 4 || n == 8;
}

// The pattern of `n` samples (isSampleCount(n)).
constexpr std::span<const SamplePosition> samplePattern(int n) {
  switch (n) {
    case 2:
      return kSamples2;
    case 4:
      return kSamples4;
    case 8:
      return kSamples8;
    default:
      return kSamples1;
  }
}

// The radical inverse of i in base b: the Halton sequence's i-th value, in [0, 1).
constexpr float radicalInverse(uint32_t i, uint32_t base) {
  float inverse = 1.0f / static_cast<float>(base), scale = inverse, value = 0.0f;
  while (i > 0) {
    value += static_cast<float>(i % base) * scale;
    i /= base;
    scale *= inverse;
  }
  return value;
}

// A sub-pixel offset of the whole sample pattern, in pixels (x right, y down), for jittered frame
// `index` of an accumulation: Halton (2, 3) centred on the pixel, snapped to 1/256 pixel. Frame 0
// is not moved, so the first frame of an accumulation is the plain image (and gives the AOVs).
struct Jitter {
  float x = 0, y = 0;
};
constexpr Jitter jitterOffset(uint32_t index) {
  if (index == 0) return {};
  auto snap = [](float v) {
    return static_cast<float>(static_cast<int32_t>(v * 256.0f + (v < 0 ? -0.5f : 0.5f))) / 256.0f;
  };
  return {snap(radicalInverse(index, 2) - 0.5f), snap(radicalInverse(index, 3) - 0.5f)};
}

// The projection that moves the sample pattern by j pixels (x right, y down) on a width x height
// viewport: the geometry moves by -j instead, a clip-space translation after the projection
// (x' = x + t w), so every vertex's window position moves by exactly -j before it is snapped.
inline float4x4 jitteredProjection(const float4x4& projection, Jitter j, int width, int height) {
  if (j.x == 0.0f && j.y == 0.0f) return projection;
  float4x4 shift = float4x4::identity();
  // NDC x = 2 wx / W - 1 and y = 1 - 2 wy / H: moving the geometry by -j pixels.
  shift(0, 3) = -2.0f * j.x / static_cast<float>(width);
  shift(1, 3) = 2.0f * j.y / static_cast<float>(height);
  return shift * projection;
}

}  // namespace tessera
