// Run-time choice of the raster kernel's instruction set.
#include "render/raster.h"

namespace tessera::render {

RasterIsa detectRasterIsa() {
#if defined(__x86_64__) || defined(__i386__)
  __builtin_cpu_init();
  if (__builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512vl") &&
      __builtin_cpu_supports("avx512bw") && __builtin_cpu_supports("avx512dq"))
    return RasterIsa::kAvx512;
  if (__builtin_cpu_supports("avx2")) return RasterIsa::kAvx2;
  return RasterIsa::kSse2;
#else
  return RasterIsa::kScalar;
#endif
}

const char* rasterIsaName(RasterIsa isa) {
  switch (isa) {
    case RasterIsa::kScalar: return "scalar";
    case RasterIsa::kSse2: return "sse2";
    case RasterIsa::kAvx2: return "avx2";
    case RasterIsa::kAvx512: return "avx512";
  }
  return "?";
}

RasterTriangleFn rasterTriangleFunction(RasterIsa isa) {
  switch (isa) {
    case RasterIsa::kScalar: return rasterTriangleScalar;
#if defined(__x86_64__) || defined(__i386__)
    case RasterIsa::kSse2: return rasterTriangleSse2;
    case RasterIsa::kAvx2: return rasterTriangleAvx2;
    case RasterIsa::kAvx512: return rasterTriangleAvx512;
#else
    default: return rasterTriangleScalar;
#endif
  }
  return rasterTriangleScalar;
}

}  // namespace tessera::render
