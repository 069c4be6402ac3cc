// The ray passes of the nonlinear projections (cylindrical, spherical, stereographic, fisheye):
// a pixel is covered when its view ray passes through the triangle, tested with three planes
// through the eye (src/render/ray_setup.h, whose arithmetic this repeats in the same order, with
// `precise` so that no multiply-add is fused: the same bits as the CPU). Included by records.glsl
// when TESSERA_RAY = 1.

// render::RayTriangle: edge normals n_k, det = q0 . n0 > 0, up to two inclusive pixel boxes (the
// second empty, min_x > max_x, unless the triangle crosses the seam of a 360-degree image).
struct RayRecord {
  float n[9];  // n[3 k + i]: component i of n_k
  float det;
  uint key;    // scene triangle index << 3
  uint owner;  // bit k: rays exactly on edge k (E_k == 0) are covered
  ivec4 box[2];  // min_x, min_y, max_x, max_y
};

layout(std430, set = 0, binding = 9) buffer RayRecordBuffer { RayRecord ray_records[]; };
// The host's RayTable, rounded to float as the CPU's: ray layer 0 holds the pixel centres' rays,
// layers 1..samples the samples' (with one sample the centre is the sample: one layer). Each
// layer is x, y, z per pixel, row-major from the top row; a pixel with no ray holds (0, 0, 0).
layout(std430, set = 0, binding = 19) readonly buffer RayBuffer { float rays[]; };

// The ray layer of visibility layer `layer` (see gpu_types.h: the pixel centre first when the
// frame keeps it, then the samples).
uint rayLayerOf(uint layer) {
  return frame.samples == 1u ? 0u : layer + 1u - frame.first_sample_layer;
}

vec3 rayAt(uint ray_layer, uint pixel) {
  const uint at = 3u * (ray_layer * uint(frame.width) * uint(frame.height) + pixel);
  return vec3(rays[at], rays[at + 1u], rays[at + 2u]);
}

// render::dotRay: (a.x b.x + a.y b.y) + a.z b.z.
float dotRay(vec3 a, vec3 b) {
  precise float d = (a.x * b.x + a.y * b.y) + a.z * b.z;
  return d;
}

// render::crossRay.
vec3 crossRay(vec3 a, vec3 b) {
  precise vec3 c = vec3(a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x);
  return c;
}

vec3 rayNormal(RayRecord r, int k) { return vec3(r.n[3 * k], r.n[3 * k + 1], r.n[3 * k + 2]); }

// The coverage rule for E_k = d . n_k: positive, or zero on an edge the triangle owns.
bool edgeCovers(float e, uint owner, int k) {
  return e > 0.0 || (e == 0.0 && ((owner >> uint(k)) & 1u) != 0u);
}

// render::rayCovers: whether ray d passes through the triangle (no depth range).
bool rayCovers(RayRecord r, vec3 d) {
  const float e0 = dotRay(d, rayNormal(r, 0));
  const float e1 = dotRay(d, rayNormal(r, 1));
  const float e2 = dotRay(d, rayNormal(r, 2));
  precise float s = (e0 + e1) + e2;
  return edgeCovers(e0, r.owner, 0) && edgeCovers(e1, r.owner, 1) && edgeCovers(e2, r.owner, 2) &&
         s > 0.0;
}

// render::rayBarycentrics: (b0, b1, b2) of ray d's hit.
vec3 rayBarycentrics(RayRecord r, vec3 d) {
  const float e0 = dotRay(d, rayNormal(r, 0));
  const float e1 = dotRay(d, rayNormal(r, 1));
  const float e2 = dotRay(d, rayNormal(r, 2));
  precise float inv_s = 1.0 / ((e0 + e1) + e2);
  precise float b1 = e1 * inv_s;
  precise float b2 = e2 * inv_s;
  precise float b0 = 1.0 - b1 - b2;
  return vec3(b0, b1, b2);
}
