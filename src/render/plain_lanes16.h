// Two groups of eight pixels of several plain triangles shaded side by side in sixteen lanes (a
// 512-bit register each), for the AVX-512 kernels (TESSERA_LANES16): shadeMixed's loads,
// transposes, barycentrics and colours once for both groups instead of once for each, with one
// division of sixteen lanes where each group took its own. The same float operations per lane as
// shadeMixed, so the same bits.
#pragma once

#if defined(TESSERA_LANES16)

#include "render/mixed_lanes.h"
#include "render/texture_lanes16.h"

namespace tessera::render {
namespace {  // one private copy per translation unit, each compiled for its instruction set

// shadeMixed of the records of group a (`ra`, at points pxa, pya) and of group b (`rb`, at pxb,
// pyb), into ca and cb: two groups of a row, or two rounds of a row's queued fragments
// (fragment_queue.h). Groups whose every triangle is solid take shadeMixed's shortcut, each on its
// own.
TESSERA_LANES_INLINE void shadeMixedPair(const ShadeTriangle* const ra[8], F32x8 pxa, F32x8 pya,
                                         const ShadeTriangle* const rb[8], F32x8 pxb, F32x8 pyb,
                                         Vec3x8& ca, Vec3x8& cb) {
  if (allSolid(ra) || allSolid(rb)) {
    ca = shadeMixed(ra, pxa, pya);
    cb = shadeMixed(rb, pxb, pyb);
    return;
  }
  F32x16 f[kPlainFields];
  for (int block = 0; block < 2; ++block) {
    for (int l = 0; l < 8; ++l)
      f[block * 8 + l] =
          join16(load<F32x8>(&ra[l]->x0 + block * 8), load<F32x8>(&rb[l]->x0 + block * 8));
    transpose8x8Halves(f + block * 8);
  }
  const float* last_a[8];
  const float* last_b[8];
  for (int l = 0; l < 8; ++l) {
    last_a[l] = &ra[l]->x0 + 16;
    last_b[l] = &rb[l]->x0 + 16;
  }
  F32x8 ya, za, yb, zb;
  loadPairs(last_a, ya, za);
  loadPairs(last_b, yb, zb);
  f[16] = join16(ya, yb);
  f[17] = join16(za, zb);
  const F32x16 dx = join16(pxa, pxb) - f[0];
  const F32x16 dy = join16(pya, pyb) - f[1];
  const F32x16 inv_s = splat16(1.0f) / ((f[2] + f[7] * dx) + f[8] * dy);
  const F32x16 b1 = (f[3] * dx + f[4] * dy) * inv_s;
  const F32x16 b2 = (f[5] * dx + f[6] * dy) * inv_s;
  F32x16 c[3];
  for (int k = 0; k < 3; ++k)
    c[k] = f[9 + k] + (f[12 + k] - f[9 + k]) * b1 + (f[15 + k] - f[9 + k]) * b2;
  ca = {lowHalf(c[0]), lowHalf(c[1]), lowHalf(c[2])};
  cb = {highHalf(c[0]), highHalf(c[1]), highHalf(c[2])};
}

}  // namespace
}  // namespace tessera::render

#endif  // TESSERA_LANES16
