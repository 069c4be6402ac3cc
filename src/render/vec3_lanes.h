// Three-component vectors of eight lanes and the few operations on them that the shading code
// (shade_lanes.h) and the environment light (environment_lanes.h) share, each with the float
// operations of its scalar twin in render/pbr.h and <cmath>.
#pragma once

#include "render/simd_lanes.h"

namespace tessera::render {
namespace {  // one private copy per translation unit, each compiled for its instruction set

struct Vec3x8 {
  F32x8 x, y, z;
};

// As std::clamp(v, lo, hi).
TESSERA_LANES_INLINE F32x8 clampLanes(F32x8 v, float lo, float hi) {
  return select(lessThan(v, splat(lo)), splat(lo), select(lessThan(splat(hi), v), splat(hi), v));
}

// As std::fabs: the sign bit cleared.
TESSERA_LANES_INLINE F32x8 absLanes(F32x8 v) {
  return fromBits(bitsOf(v) & splat(int32_t{0x7fffffff}));
}

// As dot3 (pbr.h).
TESSERA_LANES_INLINE F32x8 dot8(const Vec3x8& a, const Vec3x8& b) {
  return (a.x * b.x + a.y * b.y) + a.z * b.z;
}

}  // namespace
}  // namespace tessera::render
