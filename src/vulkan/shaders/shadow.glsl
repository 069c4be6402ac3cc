// Shadow maps (RenderOptions::shadows) for both Vulkan backends: the CPU's ShadowMaps::visibility
// and ShadowView::project (src/render/shadow_map.cpp) over maps the CPU's own ShadowMaps::build
// drew, uploaded each frame as one block of 32-bit words (binding 21; the layout is
// GpuShadowBlock in src/vulkan/shadow_upload.h). The same cascade choice, normal offset, bias,
// 3x3 bilinear-weighted PCF and float operations in the same order (precise: no fused
// multiply-adds), so that a pixel sees the CPU's taps. Included by shading.glsl after
// irradiance(); needs Light, lights[], frame and localFactor.

layout(std430, set = 0, binding = 21) readonly buffer ShadowBuffer { uint shadow_words[]; };

// GpuShadowBlock: the header's words, a light's two words and a view's words.
const uint kShadowLightCount = 0u;
const uint kShadowOmnidirectional = 1u;
const uint kShadowNormalOffset = 2u;
const uint kShadowViews = 3u;
const uint kShadowEye = 4u;
const uint kShadowEyeForward = 7u;
const uint kShadowHeaderWords = 16u;
const uint kShadowViewWords = 24u;
const uint kViewPerspective = 0u;
const uint kViewOrigin = 1u;
const uint kViewRight = 4u;
const uint kViewUp = 7u;
const uint kViewForward = 10u;
const uint kViewCx = 13u;  // then cy, scale, z_a, z_b, near_d, texel_world, reach
const uint kViewSize = 21u;
const uint kViewDepth = 22u;

float shadowFloat(uint i) { return uintBitsToFloat(shadow_words[i]); }
vec3 shadowVec3(uint i) { return vec3(shadowFloat(i), shadowFloat(i + 1u), shadowFloat(i + 2u)); }

// ShadowView: the projection into one map (see shadow_map.h for the fields).
struct ShadowView {
  bool perspective;
  vec3 origin, right, up, forward;
  float cx, cy, scale, z_a, z_b, near_d, texel_world, reach;
  int size;
  uint depth;  // the first texel's word
};

ShadowView shadowView(int index) {
  const uint w = shadow_words[kShadowViews] + uint(index) * kShadowViewWords;
  ShadowView v;
  v.perspective = shadow_words[w + kViewPerspective] != 0u;
  v.origin = shadowVec3(w + kViewOrigin);
  v.right = shadowVec3(w + kViewRight);
  v.up = shadowVec3(w + kViewUp);
  v.forward = shadowVec3(w + kViewForward);
  v.cx = shadowFloat(w + kViewCx);
  v.cy = shadowFloat(w + kViewCx + 1u);
  v.scale = shadowFloat(w + kViewCx + 2u);
  v.z_a = shadowFloat(w + kViewCx + 3u);
  v.z_b = shadowFloat(w + kViewCx + 4u);
  v.near_d = shadowFloat(w + kViewCx + 5u);
  v.texel_world = shadowFloat(w + kViewCx + 6u);
  v.reach = shadowFloat(w + kViewCx + 7u);
  v.size = int(shadow_words[w + kViewSize]);
  v.depth = shadow_words[w + kViewDepth];
  return v;
}

// tessera's dot(float3, float3): (x + y) + z.
float shadowDot(vec3 a, vec3 b) {
  precise float d = a.x * b.x + a.y * b.y + a.z * b.z;
  return d;
}

// ShadowView::project: p in map coordinates (texels, window depth); false behind a perspective
// map's near plane.
bool shadowProject(ShadowView view, vec3 p, out vec3 m) {
  precise vec3 d = p - view.origin;
  const vec3 l = vec3(shadowDot(d, view.right), shadowDot(d, view.up), shadowDot(d, view.forward));
  m = vec3(0.0);
  if (view.perspective && !(l.z > view.near_d)) return false;
  precise float half_size = float(view.size) * 0.5;
  if (!view.perspective) {
    precise vec3 o = vec3((l.x - view.cx) * view.scale + half_size,
                          (view.cy - l.y) * view.scale + half_size, (l.z - view.z_a) * view.z_b);
    m = o;
    return true;
  }
  precise float inv_d = 1.0 / l.z;
  precise vec3 o = vec3(l.x * inv_d * view.scale + half_size, -l.y * inv_d * view.scale + half_size,
                        view.z_a - view.z_b * inv_d);
  m = o;
  return true;
}

// The 3x3 texels around map point m, each weighted by its bilinear overlap (taps ix - 1 .. ix + 2
// with weights 1 - fx, 1, 1, fx, and as much in y), over 9: the share of light that passes.
float shadowFilter(ShadowView view, vec3 m) {
  precise float x = m.x - 0.5, y = m.y - 0.5;
  const float fx_floor = floor(x), fy_floor = floor(y);
  precise float fx = x - fx_floor, fy = y - fy_floor;
  const int ix = int(fx_floor), iy = int(fy_floor);
  precise float wx[4] = float[4](1.0 - fx, 1.0, 1.0, fx);
  precise float wy[4] = float[4](1.0 - fy, 1.0, 1.0, fy);
  precise float occluded = 0.0;
  for (int j = 0; j < 4; ++j) {
    const uint row = view.depth + uint(iy - 1 + j) * uint(view.size) + uint(ix - 1);
    for (int k = 0; k < 4; ++k)
      if (m.z > shadowFloat(row + uint(k))) occluded = occluded + wx[k] * wy[j];
  }
  precise float visible = 1.0 - occluded * (1.0 / 9.0);
  return visible;
}

// ShadowMaps::visibility for scene light `light` (1 where it has no maps): how much of it reaches
// world point p with unit normal n. The first cascade whose reach holds the point's view depth
// (or distance, omnidirectional) and whose map holds the filter's footprint decides.
float shadowVisibility(uint light, vec3 p, vec3 n) {
  if (light >= shadow_words[kShadowLightCount]) return 1.0;
  const int first = int(shadow_words[kShadowHeaderWords + 2u * light]);
  const int count = int(shadow_words[kShadowHeaderWords + 2u * light + 1u]);
  if (first < 0) return 1.0;
  precise vec3 from_eye = p - shadowVec3(kShadowEye);
  precise float depth = shadow_words[kShadowOmnidirectional] != 0u
                            ? sqrt(shadowDot(from_eye, from_eye))
                            : shadowDot(from_eye, shadowVec3(kShadowEyeForward));
  const float normal_offset = shadowFloat(kShadowNormalOffset);
  for (int i = first; i < first + count; ++i) {
    const ShadowView view = shadowView(i);
    if (!(depth <= view.reach)) continue;
    precise float texel = view.texel_world;
    if (view.perspective) {
      precise vec3 from_light = p - view.origin;
      texel = texel * shadowDot(from_light, view.forward);
    }
    precise vec3 moved = p + n * (texel * normal_offset);
    vec3 m;
    if (!shadowProject(view, moved, m)) return 1.0;
    precise float limit = float(view.size) - 1.5;
    if (!(m.x >= 1.5 && m.x < limit && m.y >= 1.5 && m.y < limit)) continue;
    return shadowFilter(view, m);
  }
  return 1.0;
}

// irradiance() with every light's share times its shadow maps' visibility (shade_lanes.h:
// irradiance8 and shadowed8): Phong pixels. Flat faces and Gouraud vertices stay unshadowed, as on
// the CPU.
vec3 irradianceShadowed(vec3 n, vec3 p) {
  precise vec3 e = frame.ambient.xyz;
  for (uint i = 0u; i < frame.light_count; ++i) {
    const Light light = lights[i];
    precise float f = lambertFactor(light, n, p);
    if (!(f > 0.0)) continue;
    f = f * shadowVisibility(i, p, n);
    e = e + light.color.xyz * f;
  }
  return e;
}
