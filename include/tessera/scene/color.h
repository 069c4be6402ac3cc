// sRGB transfer functions (IEC 61966-2-1). Shading is linear; encoding happens once, at output.
#pragma once

#include <cstdint>

#include <tessera/math/vec.h>

namespace tessera {

// Exact conversions (slow path, used for tests and tables).
float srgbToLinear(float encoded);
float linearToSrgb(float linear);

// The linear value of each 8-bit sRGB code.
const float* srgbDecodeTable();
inline float decodeSrgb8(uint8_t code) { return srgbDecodeTable()[code]; }

// Linear [0, 1] (clamped) to the nearest 8-bit sRGB code, through a 65536-entry table:
// within 0.06 of a code step of the exact encode, and exact for every decoded 8-bit value.
uint8_t encodeSrgb8(float linear);

// Linear RGBA to packed RGBA8 (sRGB RGB, linear alpha), R in the low byte.
uint32_t packSrgba8(float4 linear);

}  // namespace tessera
