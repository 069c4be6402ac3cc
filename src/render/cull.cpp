#include "render/cull.h"

#include <algorithm>
#include <cmath>

#include <tessera/scene/clusters.h>

#include "render/fixed_point.h"

namespace tessera::render {

namespace {

// Relative margin of the plane tests: the vertex stage computes clip coordinates in float
// (a few ulps of the products' magnitude); the boxes are tested in double with 20 times that.
constexpr double kPlaneMargin = 1e-5;

// kOutside when every point of `box` (mesh space) is outside one plane the outcodes test
// (x < -w, x > w, y < -w, y > w, z < -w, z > w), kInside when every point is inside all six,
// each with a margin for float rounding. A plane's value over the box is a linear function:
// its value at the centre plus or minus the sum of |coefficient| * half-extent.
Side sideOf(const Bounds& box, const float4x4& mvp) {
  if (box.empty()) return Side::kOutside;  // no vertex a triangle could draw with
  const double centre[3] = {0.5 * (double(box.min.x) + box.max.x),
                            0.5 * (double(box.min.y) + box.max.y),
                            0.5 * (double(box.min.z) + box.max.z)};
  const double half[3] = {0.5 * (double(box.max.x) - box.min.x),
                          0.5 * (double(box.max.y) - box.min.y),
                          0.5 * (double(box.max.z) - box.min.z)};
  const double reach[3] = {std::fabs(centre[0]) + half[0], std::fabs(centre[1]) + half[1],
                           std::fabs(centre[2]) + half[2]};
  // Per row of the matrix: its value at the centre, and the size of the terms the vertex stage
  // adds in float at the farthest corner.
  double m[4][4], at_centre[4], size[4];
  for (int r = 0; r < 4; ++r) {
    for (int j = 0; j < 4; ++j) m[r][j] = mvp(r, j);
    at_centre[r] = m[r][3] + m[r][0] * centre[0] + m[r][1] * centre[1] + m[r][2] * centre[2];
    size[r] = std::fabs(m[r][3]) + std::fabs(m[r][0]) * reach[0] + std::fabs(m[r][1]) * reach[1] +
              std::fabs(m[r][2]) * reach[2];
  }
  // Plane i is row 3 + sign * row axis: w + x, w - x, w + y, w - y, w + z, w - z (inside: >= 0).
  bool inside = true;
  for (int i = 0; i < 6; ++i) {
    const int axis = i / 2;
    const double sign = i % 2 ? -1.0 : 1.0;
    const double value = at_centre[3] + sign * at_centre[axis];
    const double spread = std::fabs(m[3][0] + sign * m[axis][0]) * half[0] +
                          std::fabs(m[3][1] + sign * m[axis][1]) * half[1] +
                          std::fabs(m[3][2] + sign * m[axis][2]) * half[2];
    const double margin = kPlaneMargin * (size[3] + size[axis]);
    if (!std::isfinite(value) || !std::isfinite(spread) || !std::isfinite(margin))
      return Side::kCrossing;
    if (value + spread < -margin) return Side::kOutside;
    inside = inside && value - spread > margin;
  }
  return inside ? Side::kInside : Side::kCrossing;
}

// A cluster's box as the rasterizer will see it.
struct ScreenBox {
  bool unclipped = false;  // wholly inside near, far and the guard band: no triangle is clipped
  double w_min = INFINITY, w_max = 0;  // the range of clip w over its points
  double ndc_max[2] = {0, 0};          // the largest |x / w| and |y / w| of its points
  double error = 0;  // how far a vertex's snapped position may be from the exact one, pixels
};

ScreenBox screenBoxOf(const Bounds& box, const float4x4& mvp, const CullViewport& viewport) {
  ScreenBox out;
  if (box.empty()) return out;
  const double half_w = 0.5 * viewport.width, half_h = 0.5 * viewport.height;
  const double guard_x = 1.0 + 2.0 * kGuardBandPixels / viewport.width;
  const double guard_y = 1.0 + 2.0 * kGuardBandPixels / viewport.height;
  double float_error = 0;
  for (int k = 0; k < 8; ++k) {
    const double p[3] = {k & 1 ? box.max.x : box.min.x, k & 2 ? box.max.y : box.min.y,
                         k & 4 ? box.max.z : box.min.z};
    double c[4], m[4];
    for (int r = 0; r < 4; ++r) {
      c[r] = double(mvp(r, 3));
      m[r] = std::fabs(double(mvp(r, 3)));
      for (int j = 0; j < 3; ++j) {
        c[r] += double(mvp(r, j)) * p[j];
        m[r] += std::fabs(double(mvp(r, j)) * p[j]);
      }
    }
    const double slack = kPlaneMargin * (m[3] + std::max({m[0], m[1], m[2]}));
    const bool inside = c[3] > slack && c[3] + c[2] > slack && c[3] - c[2] > slack &&
                        guard_x * c[3] - std::fabs(c[0]) > guard_x * slack &&
                        guard_y * c[3] - std::fabs(c[1]) > guard_y * slack;
    if (!inside || !std::isfinite(c[0] + c[1] + c[3] + m[0] + m[1] + m[3])) return out;
    // The box's projection is the hull of its corners': the extremes are corners'.
    const double x = (c[0] / c[3] + 1) * half_w, y = (1 - c[1] / c[3]) * half_h;
    out.ndc_max[0] = std::max(out.ndc_max[0], std::fabs(c[0] / c[3]) * (1 + 1e-6));
    out.ndc_max[1] = std::max(out.ndc_max[1], std::fabs(c[1] / c[3]) * (1 + 1e-6));
    out.w_min = std::min(out.w_min, c[3] - kPlaneMargin * m[3]);
    out.w_max = std::max(out.w_max, c[3] + kPlaneMargin * m[3]);
    // The vertex stage's float rounding (clip coordinates, the division, the viewport) as a
    // relative 1e-6 of every term, far above the few ulps it is.
    float_error =
        std::max({float_error,
                  1e-6 * (std::fabs(x) + half_w * (m[0] + std::fabs(c[0] / c[3]) * m[3]) / c[3]),
                  1e-6 * (std::fabs(y) + half_h * (m[1] + std::fabs(c[1] / c[3]) * m[3]) / c[3])});
  }
  out.unclipped = out.w_min > 0;
  out.error = 0.5 / kSubpixelOne + float_error;
  return out;
}

// Where the faces are seen from, in a mesh's space: the eye (perspective) or the direction the
// camera looks along, L^-1 (0, 0, -1) (orthographic), with L the model-view's 3x3; and the
// factors that turn a triangle's mesh-space double area into pixels squared.
struct Viewpoint {
  bool valid = false;
  bool directional = false;
  double p[3] = {0, 0, 0};
  double sign = 1;        // folds in the mirroring of the model matrix and which faces cull
  double area_scale = 0;  // (W/2)(H/2) |P00 P11| |det L|
};

// True when every triangle of the cluster faces away (the side the renderer culls) by enough
// that the snapped vertices cannot turn it. The rasterizer culls by the sign of the snapped
// double area; each vertex moves by at most e = box.error per axis, which changes the double
// area of a triangle with edges u, v by at most 2 e (|u|1 + |v|1) + 8 e^2. In pixels, an edge of
// mesh length l is at most k l long (|u|1, |v|1 <= k L for the triangle's longest edge L), with
//   k = ((W/2)(|row 0| + ndc_x |row 3|) + (H/2)(|row 1| + ndc_y |row 3|)) / w_min
// (rows of the model-view-projection, ndc the box's largest |x/w|, |y/w|). The exact double area
// is at least K h L, with h the triangle's altitude to that edge (mesh space), and
//   perspective:  K = area_scale * min n.(p - eye) / w_max^3
//   orthographic: K = area_scale * min n.d
// (det[P0 P1 P2] / (w0 w1 w2) in camera space is det L (u x v).(p - eye) in mesh space). So the
// sign holds, with a factor 2 to spare, when K h_min > 2 (4 e k + 8 e^2 / L_min).
bool facesAway(const MeshCluster& cluster, const Viewpoint& eye, const float4x4& mvp,
               const CullViewport& viewport) {
  if (!eye.valid || !(cluster.cone_cos > 0.0f) || !(cluster.min_altitude > 0.0f) ||
      !(cluster.min_edge > 0.0f) || cluster.bounds.empty())
    return false;
  const double cos_a = cluster.cone_cos, sin_a = std::sqrt(std::max(0.0, 1 - cos_a * cos_a));
  const double axis[3] = {eye.sign * cluster.cone_axis.x, eye.sign * cluster.cone_axis.y,
                          eye.sign * cluster.cone_axis.z};
  const double axis_len = std::sqrt(axis[0] * axis[0] + axis[1] * axis[1] + axis[2] * axis[2]);
  if (!(axis_len > 0.5)) return false;
  // v: from the eye to the cluster's centre (or the view direction); n.v >= |v| cos(b + a) - r
  // for every face normal n within the cone and every point within r of the centre.
  const float3 c = cluster.bounds.center();
  const double r = eye.directional ? 0.0 : double(cluster.bounds.radius()) * (1 + 1e-6);
  const double v[3] = {eye.directional ? eye.p[0] : c.x - eye.p[0],
                       eye.directional ? eye.p[1] : c.y - eye.p[1],
                       eye.directional ? eye.p[2] : c.z - eye.p[2]};
  const double dist = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  if (!(dist > 0) || !std::isfinite(dist)) return false;
  const double cos_b = (v[0] * axis[0] + v[1] * axis[1] + v[2] * axis[2]) / (dist * axis_len);
  const double sin_b = std::sqrt(std::max(0.0, 1 - cos_b * cos_b));
  // 1e-6: the axis is a float rounding of a unit vector.
  const double facing = dist * (cos_b * cos_a - sin_b * sin_a - 1e-6) - r;
  if (!(facing > 0)) return false;
  const ScreenBox box = screenBoxOf(cluster.bounds, mvp, viewport);
  if (!box.unclipped) return false;
  double gain = eye.area_scale * facing;  // K
  if (!eye.directional) gain /= box.w_max * box.w_max * box.w_max;
  const auto rowLength = [&](int row) {
    return std::sqrt(double(mvp(row, 0)) * mvp(row, 0) + double(mvp(row, 1)) * mvp(row, 1) +
                     double(mvp(row, 2)) * mvp(row, 2));
  };
  const double w = rowLength(3);
  const double stretch = (0.5 * viewport.width * (rowLength(0) + box.ndc_max[0] * w) +
                          0.5 * viewport.height * (rowLength(1) + box.ndc_max[1] * w)) /
                         box.w_min;  // k
  const double e = box.error;
  const double change = 4 * e * stretch + 8 * e * e / cluster.min_edge;
  return std::isfinite(gain * stretch) && gain * cluster.min_altitude > 2 * change;
}

// The viewpoint of an object, when the projection is one whose screen-space winding the test
// predicts (a perspective or orthographic row 3).
Viewpoint viewpointOf(const Object& object, const float4x4& model, const float4x4& view,
                      const float4x4& projection, const CullViewport& viewport) {
  Viewpoint out;
  const bool perspective = projection(3, 0) == 0 && projection(3, 1) == 0 &&
                           projection(3, 2) == -1 && projection(3, 3) == 0;
  const bool orthographic = projection(3, 0) == 0 && projection(3, 1) == 0 &&
                            projection(3, 2) == 0 && projection(3, 3) == 1;
  if (object.cull == CullMode::kNone || (!perspective && !orthographic)) return out;
  const float4x4 inverse_model_view = inverse(view * model);
  const float4 local = orthographic ? inverse_model_view * float4{0, 0, -1, 0}
                                    : inverse_model_view * float4{0, 0, 0, 1};
  const float3x3 l = upper3x3(view * model);
  double det = 0;  // det L, in double
  for (int j = 0; j < 3; ++j) {
    const int j1 = (j + 1) % 3, j2 = (j + 2) % 3;
    det += double(l(0, j)) * (double(l(1, j1)) * l(2, j2) - double(l(1, j2)) * l(2, j1));
  }
  if (!isFinite(local.xyz()) || !std::isfinite(det) || det == 0) return out;
  out.valid = true;
  out.directional = orthographic;
  out.p[0] = local.x, out.p[1] = local.y, out.p[2] = local.z;
  out.sign = (det < 0 ? -1.0 : 1.0) * (object.cull == CullMode::kFront ? -1.0 : 1.0);
  out.area_scale = 0.25 * viewport.width * viewport.height *
                   std::fabs(double(projection(0, 0)) * projection(1, 1)) * std::fabs(det);
  return out;
}

}  // namespace

Side FrustumCull::classify(const Object& object, size_t o, const float4x4& mvp, bool enabled) {
  const bool by_clusters =
      enabled && object.clusters && object.mesh && object.clusters->describes(*object.mesh);
  if (object.mesh)
    counts_[o] = {object.mesh->triangleCount(), object.mesh->vertexCount()};
  else
    counts_[o] = {};
  return sides_[o] = by_clusters ? sideOf(object.clusters->bounds, mvp) : Side::kNotTested;
}

size_t FrustumCull::run(const Scene& scene, const float4x4& view, const float4x4& projection,
                        const CullViewport& viewport, std::vector<ObjectTransforms>& objects) {
  triangles_.clear();
  vertices_.clear();
  first_triangle_range_.assign(1, 0);
  first_vertex_range_.assign(1, 0);
  counters_ = {};
  size_t base = 0;
  for (size_t o = 0; o < scene.objects.size(); ++o) {
    if (bases_[o] != base) bases_[o] = objects[o].triangle_base = base;
    const size_t triangle_count = counts_[o].triangles;
    const size_t vertex_count = counts_[o].vertices;
    const Side side = sides_[o];
    if (side == Side::kNotTested) {
      if (triangle_count > 0) triangles_.push_back({base, base + triangle_count});
      if (vertex_count > 0) vertices_.push_back({0, vertex_count});
    } else if (side == Side::kOutside) {
      ++counters_.instances_culled;
      counters_.triangles_in_culled_instances += triangle_count;
    } else {
      const Object& object = scene.objects[o];
      const float4x4& mvp = objects[o].model_view_projection;
      const MeshClusters* clusters = object.clusters.get();
      const Viewpoint eye = viewpointOf(object, objects[o].model, view, projection, viewport);
      const size_t vertex_start = vertices_.size();
      for (const MeshCluster& cluster : clusters->clusters) {
        // A mesh wholly inside the frustum has no cluster outside it.
        const bool outside = side != Side::kInside && sideOf(cluster.bounds, mvp) == Side::kOutside;
        const bool away = !outside && facesAway(cluster, eye, mvp, viewport);
        if (outside || away) {
          ++(outside ? counters_.clusters_culled : counters_.clusters_facing);
          counters_.triangles_in_culled_clusters += cluster.triangle_count;
          continue;
        }
        const size_t first = base + cluster.first_triangle;
        if (!triangles_.empty() && triangles_.size() > first_triangle_range_.back() &&
            triangles_.back().end == first)
          triangles_.back().end = first + cluster.triangle_count;
        else
          triangles_.push_back({first, first + cluster.triangle_count});
        if (cluster.end_vertex > cluster.first_vertex)
          vertices_.push_back({cluster.first_vertex, cluster.end_vertex});
      }
      // Vertex ranges sorted and merged: each vertex is transformed once, by one job.
      std::sort(vertices_.begin() + static_cast<std::ptrdiff_t>(vertex_start), vertices_.end(),
                [](const IndexRange& a, const IndexRange& b) { return a.first < b.first; });
      size_t out = vertex_start;
      for (size_t i = vertex_start; i < vertices_.size(); ++i) {
        if (out > vertex_start && vertices_[i].first <= vertices_[out - 1].end)
          vertices_[out - 1].end = std::max(vertices_[out - 1].end, vertices_[i].end);
        else
          vertices_[out++] = vertices_[i];
      }
      vertices_.resize(out);
    }
    first_triangle_range_.push_back(triangles_.size());
    first_vertex_range_.push_back(vertices_.size());
    base += triangle_count;
  }
  return base;
}

void FrustumCull::addTo(PipelineStats& stats) const {
  stats.instances_culled = counters_.instances_culled;
  stats.clusters_culled = counters_.clusters_culled;
  stats.clusters_facing = counters_.clusters_facing;
  stats.triangles_skipped =
      counters_.triangles_in_culled_instances + counters_.triangles_in_culled_clusters;
}

size_t FrustumCull::planVertices(size_t per_job, std::vector<ObjectTransforms>& objects,
                                 std::vector<VertexJob>& jobs) {
  jobs.clear();
  size_t total = 0;
  for (size_t i = 0; i < counts_.size(); ++i) {
    const bool draws = drawsTriangles(i);  // only an object with a mesh has triangle ranges
    const size_t vertex_base = draws ? total : 0;
    if (vertex_bases_[i] != vertex_base) vertex_bases_[i] = objects[i].vertex_base = vertex_base;
    if (!draws) continue;
    for (const IndexRange* r = verticesBegin(i); r != verticesEnd(i); ++r)
      for (size_t first = r->first; first < r->end; first += per_job)
        jobs.push_back({static_cast<uint32_t>(i), first, std::min(per_job, r->end - first)});
    total += counts_[i].vertices;
  }
  return total;
}

}  // namespace tessera::render
