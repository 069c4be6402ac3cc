// Clip space to window space, shared by the transform pass (every vertex inside the guard band
// and the depth range) and setup (the vertices the clipper makes): src/render/clip.h's outcodes
// and src/render/setup.h's projectToScreen. Needs common.glsl and records.glsl.
//
// TESSERA_FP64 = 1: divisions in double, rounded once to float; = 0: in float.

// src/render/clip.h
const uint kClipNear = 1u;
const uint kClipFar = 2u;
const uint kClipLeft = 4u;
const uint kClipRight = 8u;
const uint kClipBottom = 16u;
const uint kClipTop = 32u;
const uint kGuardLeft = 64u;
const uint kGuardRight = 128u;
const uint kGuardBottom = 256u;
const uint kGuardTop = 512u;
const uint kNonFinite = 1024u;  // a NaN or infinite coordinate: the triangle is dropped
const uint kRejectPlanes = 63u;
const uint kCutPlanes = kClipNear | kClipFar | kGuardLeft | kGuardRight | kGuardBottom | kGuardTop;

// a / b rounded once to float. In double the quotient is correctly rounded even where a GPU's
// float division is allowed 2.5 ulp of error (a double quotient rounded to float is the
// correctly rounded float quotient).
float divideRounded(float a, float b) {
#if TESSERA_FP64
  precise double q = double(a) / double(b);
  return float(q);
#else
  precise float q = a / b;
  return q;
#endif
}

uint outcode(vec4 p) {
  uint code = 0u;
  if (p.z < -p.w) code |= kClipNear;
  if (p.z > p.w) code |= kClipFar;
  if (p.x < -p.w) code |= kClipLeft;
  if (p.x > p.w) code |= kClipRight;
  if (p.y < -p.w) code |= kClipBottom;
  if (p.y > p.w) code |= kClipTop;
  precise float gx = frame.guard_x * p.w;
  precise float gy = frame.guard_y * p.w;
  if (p.x < -gx) code |= kGuardLeft;
  if (p.x > gx) code |= kGuardRight;
  if (p.y < -gy) code |= kGuardBottom;
  if (p.y > gy) code |= kGuardTop;
  return code;
}

// render::ScreenVertex: window position in 1/256 pixel (y down), window depth, 1 / clip w.
struct ScreenVertex {
  int x, y;
  float z, inv_w;
};

// render::projectToScreen, the one place clip space becomes window space: snapping rounds half
// to even (lrint).
ScreenVertex projectToScreen(vec4 clip) {
  const float inv_w = divideRounded(1.0, clip.w);
  precise float wx = (clip.x * inv_w * 0.5 + 0.5) * float(frame.width);
  precise float wy = (0.5 - clip.y * inv_w * 0.5) * float(frame.height);
  precise float z = clip.z * inv_w * 0.5 + 0.5;
  precise float sx = wx * float(kSubpixelOne);
  precise float sy = wy * float(kSubpixelOne);
  return ScreenVertex(int(roundEven(sx)), int(roundEven(sy)), z, inv_w);
}

