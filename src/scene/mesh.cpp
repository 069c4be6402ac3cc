#include <tessera/scene/mesh.h>

#include <algorithm>
#include <cmath>

namespace tessera {

Bounds Mesh::bounds() const {
  Bounds b;
  for (const float3& p : positions)
    if (isFinite(p)) b.add(p);
  return b;
}

namespace {

// Cross products of edges span the square of the model's size: in float they overflow past about
// 1e19 and lose everything to underflow below about 1e-19. Models in [2^-30, 2^30] take the
// float path; others are scaled by a power of two (exact) in double first, which keeps every
// face's weight relative to the others.
constexpr double kFloatSafeExtent = 1073741824.0;  // 2^30

// A power of two near the model's largest extent, or 1 when float is safe.
double crossScale(const Mesh& mesh) {
  double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
  for (const float3& p : mesh.positions) {
    if (!isFinite(p)) continue;
    for (int i = 0; i < 3; ++i) {
      lo[i] = std::min(lo[i], double(p[i]));
      hi[i] = std::max(hi[i], double(p[i]));
    }
  }
  double extent = 0;
  for (int i = 0; i < 3; ++i) extent = std::max(extent, hi[i] - lo[i]);
  if (!(extent > 0) || (extent <= kFloatSafeExtent && extent >= 1.0 / kFloatSafeExtent)) return 1;
  return std::exp2(std::round(std::log2(extent)));
}

float3 scaledCross(float3 p0, float3 p1, float3 p2, double scale) {
  const double a[3] = {(double(p1.x) - p0.x) / scale, (double(p1.y) - p0.y) / scale,
                       (double(p1.z) - p0.z) / scale};
  const double b[3] = {(double(p2.x) - p0.x) / scale, (double(p2.y) - p0.y) / scale,
                       (double(p2.z) - p0.z) / scale};
  return {static_cast<float>(a[1] * b[2] - a[2] * b[1]),
          static_cast<float>(a[2] * b[0] - a[0] * b[2]),
          static_cast<float>(a[0] * b[1] - a[1] * b[0])};
}

}  // namespace

float3 safeNormalize(float3 v) {
  float3 unit = normalize(v);
  if (length(unit) > 0.0f && isFinite(unit)) return unit;
  // The length overflowed or underflowed: divide by the largest component first.
  const float largest = std::max({std::abs(v.x), std::abs(v.y), std::abs(v.z)});
  if (!(largest > 0.0f) || !std::isfinite(largest)) return float3{0, 0, 0};
  unit = normalize(v / largest);
  return isFinite(unit) ? unit : float3{0, 0, 0};
}

void generateSmoothNormals(Mesh& mesh) {
  mesh.normals.assign(mesh.positions.size(), float3{});
  const size_t vertex_count = mesh.positions.size();
  const double scale = crossScale(mesh);
  for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
    uint32_t i0 = mesh.indices[t], i1 = mesh.indices[t + 1], i2 = mesh.indices[t + 2];
    if (i0 >= vertex_count || i1 >= vertex_count || i2 >= vertex_count) continue;
    float3 p0 = mesh.positions[i0], p1 = mesh.positions[i1], p2 = mesh.positions[i2];
    // The unnormalized cross product is twice the area: larger faces weigh more.
    float3 n = scale == 1 ? cross(p1 - p0, p2 - p0) : scaledCross(p0, p1, p2, scale);
    if (!isFinite(n)) continue;
    mesh.normals[i0] += n;
    mesh.normals[i1] += n;
    mesh.normals[i2] += n;
  }
  for (float3& n : mesh.normals) {
    float3 unit = safeNormalize(n);
    n = length(unit) > 0.0f ? unit : float3{0, 0, 1};
  }
}

void generateTangents(Mesh& mesh, int uv_set) {
  const size_t vertex_count = mesh.positions.size();
  mesh.tangents.clear();
  const std::vector<float2>& uvs =
      uv_set == 1 && mesh.uvs1.size() == vertex_count ? mesh.uvs1 : mesh.uvs;
  if (mesh.normals.size() != vertex_count || uvs.size() != vertex_count) return;
  // Each triangle adds its dP/du and dP/dv (from its edges and their UV differences) to its
  // corners.
  std::vector<float3> du(vertex_count, float3{}), dv(vertex_count, float3{});
  for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
    const uint32_t i[3] = {mesh.indices[t], mesh.indices[t + 1], mesh.indices[t + 2]};
    if (i[0] >= vertex_count || i[1] >= vertex_count || i[2] >= vertex_count) continue;
    const float3 e1 = mesh.positions[i[1]] - mesh.positions[i[0]];
    const float3 e2 = mesh.positions[i[2]] - mesh.positions[i[0]];
    const float2 d1 = uvs[i[1]] - uvs[i[0]], d2 = uvs[i[2]] - uvs[i[0]];
    const float det = d1.x * d2.y - d2.x * d1.y;
    if (!(std::fabs(det) > 0.0f)) continue;
    const float inv = 1.0f / det;
    const float3 tu = (e1 * d2.y - e2 * d1.y) * inv, tv = (e2 * d1.x - e1 * d2.x) * inv;
    if (!isFinite(tu) || !isFinite(tv)) continue;
    for (uint32_t k : i) {
      du[k] += tu;
      dv[k] += tv;
    }
  }
  mesh.tangents.resize(vertex_count);
  for (size_t v = 0; v < vertex_count; ++v) {
    const float3 n = mesh.normals[v];
    float3 t = safeNormalize(du[v] - n * dot(n, du[v]));
    // No UV gradient here: any direction across the normal.
    if (length(t) == 0.0f)
      t = safeNormalize(std::fabs(n.x) < 0.9f ? cross(n, float3{1, 0, 0})
                                              : cross(n, float3{0, 1, 0}));
    const float w = dot(cross(n, t), dv[v]) < 0.0f ? -1.0f : 1.0f;
    mesh.tangents[v] = float4(t, w);
  }
}

}  // namespace tessera
