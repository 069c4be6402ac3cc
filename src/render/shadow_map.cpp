// Shadow maps: fitting (cascades, spot cones), a scalar depth-only rasterizer, and the filtered
// lookup. See shadow_map.h.
#include "render/shadow_map.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <tessera/math/mat.h>

#include "render/lights.h"
#include "render/worker_pool.h"

namespace tessera::render {
namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();
// The cascades' split: this much of the logarithmic scheme, the rest uniform.
constexpr float kLogSplit = 0.8f;
// Slope-scaled bias is clamped at this many texels of depth (a caster seen edge-on would
// otherwise push its shadow off its base: peter-panning).
constexpr float kMaxSlopeTexels = 4.0f;

// A light-space frame: forward the way the light travels, right and up across it.
void lightBasis(float3 direction, float3& forward, float3& right, float3& up) {
  forward = normalize(direction);
  const float3 helper = std::fabs(forward.y) < 0.99f ? float3{0, 1, 0} : float3{1, 0, 0};
  right = normalize(cross(forward, helper));
  up = cross(right, forward);
}

void boundsCorners(const Bounds& b, float3 out[8]) {
  for (int i = 0; i < 8; ++i)
    out[i] = {(i & 1) ? b.max.x : b.min.x, (i & 2) ? b.max.y : b.min.y,
              (i & 4) ? b.max.z : b.min.z};
}

struct MapVertex {
  float u, v, z;
};

// Light space (lx, ly, ld) of p.
float3 toLight(const ShadowView& view, float3 p) {
  const float3 d = p - view.origin;
  return {dot(d, view.right), dot(d, view.up), dot(d, view.forward)};
}

MapVertex toMap(const ShadowView& view, float3 l) {
  const float half = static_cast<float>(view.size) * 0.5f;
  if (!view.perspective)
    return {(l.x - view.cx) * view.scale + half, (view.cy - l.y) * view.scale + half,
            (l.z - view.z_a) * view.z_b};
  const float inv_d = 1.0f / l.z;
  return {l.x * inv_d * view.scale + half, -l.y * inv_d * view.scale + half,
          view.z_a - view.z_b * inv_d};
}

// One triangle into rows [row_begin, row_end) of the map: pixel centres inside it (either
// winding, with a hair of slack so that no centre on a shared edge falls between two triangles)
// keep the nearest depth, plus the slope-scaled bias.
void rasterizeTriangle(const ShadowOptions& options, float depth_unit, const MapVertex& a,
                       const MapVertex& b, const MapVertex& c, int row_begin, int row_end,
                       ShadowView& view) {
  const double min_v = std::max<double>(row_begin, std::floor(std::min({a.v, b.v, c.v}) - 0.5));
  const double max_v = std::min<double>(row_end - 1, std::ceil(std::max({a.v, b.v, c.v}) - 0.5));
  if (min_v > max_v) return;
  const double e1u = b.u - a.u, e1v = b.v - a.v, e2u = c.u - a.u, e2v = c.v - a.v;
  const double area = e1u * e2v - e1v * e2u;
  if (!(std::fabs(area) > 1e-12) || !std::isfinite(area)) return;
  const double size = view.size;
  const double min_u = std::max(0.0, std::floor(std::min({a.u, b.u, c.u}) - 0.5));
  const double max_u = std::min(size - 1.0, std::ceil(std::max({a.u, b.u, c.u}) - 0.5));
  if (min_u > max_u) return;
  const double dzdu = ((b.z - a.z) * e2v - (c.z - a.z) * e1v) / area;
  const double dzdv = ((c.z - a.z) * e1u - (b.z - a.z) * e2u) / area;
  const double slope = std::min(std::max(std::fabs(dzdu), std::fabs(dzdv)),
                                static_cast<double>(kMaxSlopeTexels * depth_unit));
  const double bias = options.constant_bias * depth_unit + options.slope_bias * slope;
  const double sign = area > 0 ? 1.0 : -1.0;
  // Edge i at (px, py): ea[i] * px + eb[i] * py + ec[i], >= 0 inside.
  const MapVertex* from[3] = {&b, &c, &a};
  const MapVertex* to[3] = {&c, &a, &b};
  // Edge i is >= 0 where px >= (or <=, as ea[i] < 0) -(eb[i] * py + ec[i]) / ea[i]: the row's
  // crossing is cross_b[i] * py + cross_c[i].
  double ea[3], cross_b[3], cross_c[3], eb[3], ec[3];
  for (int i = 0; i < 3; ++i) {
    const double du = to[i]->u - from[i]->u, dv = to[i]->v - from[i]->v;
    ea[i] = -dv * sign;
    eb[i] = du * sign;
    ec[i] = (dv * from[i]->u - du * from[i]->v) * sign;
    const double inv = ea[i] != 0 ? -1.0 / ea[i] : 0.0;
    cross_b[i] = eb[i] * inv;
    cross_c[i] = ec[i] * inv - 0.5;
  }
  constexpr double kSlack = 1e-7;  // pixels
  for (int y = static_cast<int>(min_v); y <= static_cast<int>(max_v); ++y) {
    const double py = y + 0.5;
    // The row's span: where each edge's value, linear in px, is >= 0.
    double lo = min_u, hi = max_u;
    for (int i = 0; i < 3; ++i) {
      const double cross = cross_b[i] * py + cross_c[i];
      if (ea[i] > 0)
        lo = std::max(lo, std::ceil(cross - kSlack));
      else if (ea[i] < 0)
        hi = std::min(hi, std::floor(cross + kSlack));
      else if (eb[i] * py + ec[i] < 0)
        hi = -1.0;
    }
    if (lo > hi) continue;
    float* row = view.depth.data() + static_cast<size_t>(y) * static_cast<size_t>(view.size);
    const double z_row = a.z + dzdv * (py - a.v) + bias - dzdu * a.u;
    for (int x = static_cast<int>(lo); x <= static_cast<int>(hi); ++x)
      row[x] = std::min(row[x], static_cast<float>(z_row + dzdu * (x + 0.5)));
  }
}

// Clips the light-space polygon against ld >= near (perspective maps); returns the count.
int clipNear(const float3* in, int count, float near_d, float3* out) {
  int n = 0;
  for (int i = 0; i < count; ++i) {
    const float3 p = in[i], q = in[(i + 1) % count];
    const bool p_in = p.z >= near_d, q_in = q.z >= near_d;
    if (p_in) out[n++] = p;
    if (p_in != q_in) out[n++] = p + (q - p) * ((near_d - p.z) / (q.z - p.z));
  }
  return n;
}

bool finite3(float3 p) {
  return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z);
}

}  // namespace

bool ShadowView::project(float3 p, float3& out) const {
  const float3 l = toLight(*this, p);
  if (perspective && !(l.z > near_d)) return false;
  const MapVertex m = toMap(*this, l);
  out = {m.u, m.v, m.z};
  return true;
}

void transformShadowView(const Scene& scene, ShadowView& view) {
  size_t total = 0;
  for (const Object& object : scene.objects)
    if (object.mesh) total += object.mesh->positions.size();
  view.light_space.resize(total);
  view.depth.resize(static_cast<size_t>(view.size) * static_cast<size_t>(view.size));
  size_t base = 0;
  for (const Object& object : scene.objects) {
    if (!object.mesh) continue;
    const float4x4 model = object.transform.matrix();
    // Orthographic maps keep map coordinates (u, v, z) here already; perspective ones light
    // space, which renderShadowRows clips at the near plane first.
    for (const float3& p : object.mesh->positions) {
      const float3 l = toLight(view, (model * float4{p, 1.0f}).xyz());
      if (view.perspective) {
        view.light_space[base++] = l;
      } else {
        const MapVertex m = toMap(view, l);
        view.light_space[base++] = {m.u, m.v, m.z};
      }
    }
  }
}

void renderShadowRows(const Scene& scene, const ShadowOptions& options, int row_begin, int row_end,
                      ShadowView& view) {
  const size_t size = static_cast<size_t>(view.size);
  std::fill(view.depth.begin() + static_cast<ptrdiff_t>(static_cast<size_t>(row_begin) * size),
            view.depth.begin() + static_cast<ptrdiff_t>(static_cast<size_t>(row_end) * size), kInf);
  size_t base = 0;
  for (const Object& object : scene.objects) {
    if (!object.mesh) continue;
    const Mesh& mesh = *object.mesh;
    const float3* light_space = view.light_space.data() + base;
    const size_t count_v = mesh.positions.size();
    base += count_v;
    for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
      float3 corners[3];
      bool valid = true;
      for (int k = 0; k < 3; ++k) {
        const uint32_t index = mesh.indices[t + static_cast<size_t>(k)];
        valid = valid && index < count_v && finite3(light_space[index]);
        if (valid) corners[k] = light_space[index];
      }
      if (!valid) continue;
      if (!view.perspective) {
        // Rows outside the band: nothing to do (the common case, so tested first).
        if (std::max({corners[0].y, corners[1].y, corners[2].y}) < row_begin - 1.0f ||
            std::min({corners[0].y, corners[1].y, corners[2].y}) > row_end + 1.0f)
          continue;
        const MapVertex m[3] = {{corners[0].x, corners[0].y, corners[0].z},
                                {corners[1].x, corners[1].y, corners[1].z},
                                {corners[2].x, corners[2].y, corners[2].z}};
        rasterizeTriangle(options, view.texel_world * view.z_b, m[0], m[1], m[2], row_begin,
                          row_end, view);
        continue;
      }
      float3 polygon[4];
      const int count = clipNear(corners, 3, view.near_d, polygon);
      if (count < 3) continue;
      // One texel's depth at 45 degrees (orthographic: texel_world * z_b), at the polygon's
      // first corner: it shrinks with distance as the texels grow.
      const float d = polygon[0].z;
      const float depth_unit = view.z_b / (d * d) * (view.texel_world * d);
      MapVertex m[4];
      for (int k = 0; k < count; ++k) m[k] = toMap(view, polygon[k]);
      for (int k = 1; k + 1 < count; ++k)
        rasterizeTriangle(options, depth_unit, m[0], m[k], m[k + 1], row_begin, row_end, view);
    }
  }
}

void renderShadowView(const Scene& scene, const ShadowOptions& options, ShadowView& view) {
  transformShadowView(scene, view);
  renderShadowRows(scene, options, 0, view.size, view);
}

ShadowView& ShadowMaps::nextView(int size) {
  if (static_cast<size_t>(view_count_) == views_.size()) views_.emplace_back();
  ShadowView& view = views_[static_cast<size_t>(view_count_++)];
  // A new frame's view keeps the memory of the last one's.
  std::vector<float> depth = std::move(view.depth);
  std::vector<float3> light_space = std::move(view.light_space);
  view = ShadowView{};
  view.size = size;
  view.depth = std::move(depth);
  view.light_space = std::move(light_space);
  return view;
}

void ShadowMaps::fitCascades(const Scene& scene, const Light& light, const Bounds& bounds,
                             bool omni, float aspect, int size) {
  float3 forward, right, up;
  lightBasis(light.direction, forward, right, up);
  float3 box[8];
  boundsCorners(bounds, box);
  // The view's depth range, cut to the scene: slices beyond the farthest corner see nothing.
  const Camera& camera = scene.camera;
  const float4x4 inv_vp = inverse(camera.projection(aspect) * camera.view());
  float3 near_c[4], far_c[4];
  for (int i = 0; i < 4; ++i) {
    const float x = (i & 1) ? 1.0f : -1.0f, y = (i & 2) ? 1.0f : -1.0f;
    const float4 n = inv_vp * float4{x, y, -1.0f, 1.0f}, f = inv_vp * float4{x, y, 1.0f, 1.0f};
    near_c[i] = n.xyz() / n.w;
    far_c[i] = f.xyz() / f.w;
  }
  auto depthOf = [&](float3 p) { return omni ? length(p - eye_) : dot(p - eye_, eye_forward_); };
  const float near_d =
      omni ? std::max(camera.near_z, 0.0f) : depthOf((near_c[0] + near_c[3]) * 0.5f);
  const float far_full = omni ? camera.far_z : depthOf((far_c[0] + far_c[3]) * 0.5f);
  float scene_far = near_d;
  for (const float3& c : box) scene_far = std::max(scene_far, depthOf(c));
  const float far_d = std::min(far_full, scene_far);
  const float log_near = std::max(near_d, far_d * 1e-3f);
  float slice_near = near_d;
  for (int i = 1; i <= kCascades; ++i) {
    const float t = static_cast<float>(i) / kCascades;
    const float split = i == kCascades ? far_d
                                       : kLogSplit * (log_near * std::pow(far_d / log_near, t)) +
                                             (1.0f - kLogSplit) * (near_d + (far_d - near_d) * t);
    float3 centre = eye_;
    float radius = split;
    if (!omni) {
      // The bounding sphere of the slice's eight corners (each corner ray is linear in depth).
      float3 corner[8];
      const float span = far_full - near_d;
      for (int k = 0; k < 4; ++k) {
        corner[k] = near_c[k] + (far_c[k] - near_c[k]) * ((slice_near - near_d) / span);
        corner[k + 4] = near_c[k] + (far_c[k] - near_c[k]) * ((split - near_d) / span);
      }
      centre = float3{0, 0, 0};
      for (const float3& c : corner) centre += c * 0.125f;
      radius = 0.0f;
      for (const float3& c : corner) radius = std::max(radius, length(c - centre));
    }
    // Whole steps of 1/16 of a power of two: the map's size changes rarely as the camera moves.
    radius = std::exp2(std::ceil(std::log2(std::max(radius, 1e-6f)) * 16.0f) / 16.0f);
    ShadowView& view = nextView(size);
    view.forward = forward, view.right = right, view.up = up;
    view.texel_world = 2.0f * radius / static_cast<float>(size);
    view.scale = 1.0f / view.texel_world;
    // Snapped to whole texels (no shimmer as the camera moves).
    view.cx = std::floor(dot(centre, right) * view.scale) * view.texel_world;
    view.cy = std::floor(dot(centre, up) * view.scale) * view.texel_world;
    float z_min = dot(centre, forward) - radius, z_max = dot(centre, forward) + radius;
    for (const float3& c : box) {
      z_min = std::min(z_min, dot(c, forward));
      z_max = std::max(z_max, dot(c, forward));
    }
    const float pad = (z_max - z_min) * 0.01f + view.texel_world;
    view.z_a = z_min - pad;
    view.z_b = 1.0f / ((z_max + pad) - view.z_a);
    view.reach = split;
    slice_near = split;
  }
}

void ShadowMaps::fitSpot(const Light& light, const Bounds& bounds, int size) {
  ShadowView& view = nextView(size);
  view.perspective = true;
  view.origin = light.position;
  lightBasis(light.direction, view.forward, view.right, view.up);
  float3 box[8];
  boundsCorners(bounds, box);
  float far_d = 0.0f;
  for (const float3& c : box) far_d = std::max(far_d, length(c - light.position));
  if (light.range > 0.0f) far_d = std::min(far_d, light.range);
  far_d = std::max(far_d, 1e-4f) * 1.01f;
  view.near_d = far_d * 0.002f;
  const float tan_half = std::tan(std::min(light.outer_cone, 1.55f)) * 1.02f;
  view.scale = static_cast<float>(size) * 0.5f / tan_half;
  view.texel_world = 2.0f * tan_half / static_cast<float>(size);
  // Window z of D3D's [0, 1] perspective: far / (far - near) * (1 - near / ld).
  view.z_a = far_d / (far_d - view.near_d);
  view.z_b = view.z_a * view.near_d;
  view.reach = kInf;
}

void ShadowMaps::build(const Scene& scene, const ShadowOptions& options, bool omnidirectional,
                       float aspect, WorkerPool& pool, LightRig& rig) {
  view_count_ = 0;
  lights_.clear();
  omnidirectional_ = omnidirectional;
  normal_offset_ = options.normal_offset;
  const float4x4 camera = inverse(scene.camera.view());
  eye_ = camera.col[3].xyz();
  eye_forward_ = normalize(-camera.col[2].xyz());
  const Bounds bounds = scene.bounds();
  if (bounds.empty()) return;
  const int size = std::clamp(options.map_size, 16, 8192);
  for (size_t i = 0; i < scene.lights.size(); ++i) {
    const Light& light = scene.lights[i];
    if (light.type == LightType::kPoint) continue;
    const LightMaps maps{view_count_, light.type == LightType::kSpot ? 1 : kCascades};
    if (light.type == LightType::kSpot)
      fitSpot(light, bounds, size);
    else
      fitCascades(scene, light, bounds, omnidirectional, aspect, size);
    rig.lights[i].shadow = static_cast<int>(lights_.size());
    lights_.push_back(maps);
  }
  // Each map's vertices, then its rows in kBands bands, each band whole on one worker: a texel
  // keeps the least depth of its triangles, which no order or split changes.
  pool.parallelFor(static_cast<size_t>(view_count_),
                   [&](size_t v, int) { transformShadowView(scene, views_[v]); });
  constexpr int kBands = 4;
  pool.parallelFor(static_cast<size_t>(view_count_ * kBands), [&](size_t job, int) {
    ShadowView& view = views_[job / kBands];
    const int band = static_cast<int>(job % kBands);
    renderShadowRows(scene, options, view.size * band / kBands, view.size * (band + 1) / kBands,
                     view);
  });
  rig.shadows = this;
}

float shadowVisibility(const ShadowMaps& maps, int shadow, float3 p, float3 n) {
  return maps.visibility(shadow, p, n);
}

float ShadowMaps::visibility(int shadow, float3 p, float3 n) const {
  const LightMaps& maps = lights_[static_cast<size_t>(shadow)];
  const float depth = omnidirectional_ ? length(p - eye_) : dot(p - eye_, eye_forward_);
  for (int i = maps.first_view; i < maps.first_view + maps.view_count; ++i) {
    const ShadowView& view = views_[static_cast<size_t>(i)];
    if (!(depth <= view.reach)) continue;
    float texel = view.texel_world;
    if (view.perspective) texel = texel * dot(p - view.origin, view.forward);
    float3 m;
    if (!view.project(p + n * (texel * normal_offset_), m)) return 1.0f;
    const float limit = static_cast<float>(view.size) - 1.5f;
    if (!(m.x >= 1.5f && m.x < limit && m.y >= 1.5f && m.y < limit)) continue;
    // 3x3 texels around the point, each weighted by its bilinear overlap: taps ix - 1 .. ix + 2
    // with weights 1 - fx, 1, 1, fx (and as much in y), over 9.
    const float x = m.x - 0.5f, y = m.y - 0.5f;
    const float fx_floor = std::floor(x), fy_floor = std::floor(y);
    const float fx = x - fx_floor, fy = y - fy_floor;
    const int ix = static_cast<int>(fx_floor), iy = static_cast<int>(fy_floor);
    const float wx[4] = {1.0f - fx, 1.0f, 1.0f, fx}, wy[4] = {1.0f - fy, 1.0f, 1.0f, fy};
    float occluded = 0.0f;
    for (int j = 0; j < 4; ++j) {
      const float* row = view.depth.data() + static_cast<size_t>(iy - 1 + j) * view.size;
      for (int k = 0; k < 4; ++k) occluded += m.z > row[ix - 1 + k] ? wx[k] * wy[j] : 0.0f;
    }
    return 1.0f - occluded * (1.0f / 9.0f);
  }
  return 1.0f;
}

}  // namespace tessera::render
