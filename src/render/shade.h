// Shading: once per visible pixel, from the triangle that owns it in the visibility buffer.
#pragma once

#include <tessera/math/vec.h>
#include <tessera/scene/scene.h>

#include "render/setup.h"

namespace tessera::render {

struct ShadedPixel {
  float4 color;  // linear RGBA
  float3 normal; // world shading normal (unit)
};

// Shades window point (x, y) (a pixel centre) of triangle `t`.
ShadedPixel shadePixel(const ShadeTriangle& t, const Scene& scene, float x, float y);

}  // namespace tessera::render
