// toneMap of tone.h for eight lanes: the same operations in the same order, lane by lane, so the
// image is the same on every instruction set. Included by shade_lanes.h.
#pragma once

#include "render/simd_lanes.h"
#include "render/tone.h"

namespace tessera::render {
namespace {  // one private copy per translation unit, each compiled for its instruction set

TESSERA_LANES_INLINE F32x8 acesFit8(F32x8 v) {
  using K = ToneConstants;
  return (v * (v + splat(K::kFitA)) - splat(K::kFitB)) /
         (v * (splat(K::kFitC) * v + splat(K::kFitD)) + splat(K::kFitE));
}

// As clampUnit: a < b ? a : b written as select(lessThan(a, b), a, b), the scalar's comparisons.
TESSERA_LANES_INLINE F32x8 clampUnit8(F32x8 v) {
  const F32x8 zero = splat(0.0f), one = splat(1.0f);
  return select(lessThan(v, zero), zero, select(lessThan(one, v), one, v));
}

TESSERA_LANES_INLINE void toneAces8(F32x8& r, F32x8& g, F32x8& b) {
  using K = ToneConstants;
  const F32x8 boost = splat(K::kAcesBoost);
  r = r * boost;
  g = g * boost;
  b = b * boost;
  const float* m = K::kAcesIn;
  const F32x8 x = acesFit8((splat(m[0]) * r + splat(m[1]) * g) + splat(m[2]) * b);
  const F32x8 y = acesFit8((splat(m[3]) * r + splat(m[4]) * g) + splat(m[5]) * b);
  const F32x8 z = acesFit8((splat(m[6]) * r + splat(m[7]) * g) + splat(m[8]) * b);
  const float* o = K::kAcesOut;
  r = clampUnit8((splat(o[0]) * x + splat(o[1]) * y) + splat(o[2]) * z);
  g = clampUnit8((splat(o[3]) * x + splat(o[4]) * y) + splat(o[5]) * z);
  b = clampUnit8((splat(o[6]) * x + splat(o[7]) * y) + splat(o[8]) * z);
}

TESSERA_LANES_INLINE void tonePbrNeutral8(F32x8& r, F32x8& g, F32x8& b) {
  using K = ToneConstants;
  const F32x8 lowest = select(lessThan(g, r), g, r);
  const F32x8 x = select(lessThan(b, lowest), b, lowest);
  const F32x8 f = select(lessThan(splat(2.0f * K::kF90), x), splat(K::kF90),
                         x - (x * x) * splat(1.0f / (4.0f * K::kF90)));
  r = r - f;
  g = g - f;
  b = b - f;
  const F32x8 highest = select(lessThan(r, g), g, r);
  const F32x8 p = select(lessThan(highest, b), b, highest);
  const I32x8 compress = lessThan(splat(K::kStart), p);
  if (!any(compress)) return;
  const float d = 1.0f - K::kStart;
  const F32x8 peak = splat(1.0f) - splat(d * d) / (p + splat(d - K::kStart));
  const F32x8 w = splat(1.0f) / (splat(K::kDesaturation) * (p - peak) + splat(1.0f));
  const F32x8 s = (peak / p) * w, lift = peak * (splat(1.0f) - w);
  r = select(compress, r * s + lift, r);
  g = select(compress, g * s + lift, g);
  b = select(compress, b * s + lift, b);
}

TESSERA_LANES_INLINE void toneMap8(const ToneCurve& curve, F32x8& r, F32x8& g, F32x8& b) {
  const F32x8 scale = splat(curve.scale);
  r = r * scale;
  g = g * scale;
  b = b * scale;
  if (curve.mapping == ToneMapping::kNone) return;
  const F32x8 zero = splat(0.0f);
  r = select(lessThan(r, zero), zero, r);
  g = select(lessThan(g, zero), zero, g);
  b = select(lessThan(b, zero), zero, b);
  if (curve.mapping == ToneMapping::kAces)
    toneAces8(r, g, b);
  else
    tonePbrNeutral8(r, g, b);
}

}  // namespace
}  // namespace tessera::render
