#include "render/cull.h"

#include <algorithm>
#include <cmath>

#include <tessera/scene/clusters.h>

namespace tessera::render {

namespace {

// Relative margin of the plane tests: the vertex stage computes clip coordinates in float
// (a few ulps of the products' magnitude); the boxes are tested in double with 20 times that.
constexpr double kPlaneMargin = 1e-5;
// Back-facing clusters are rejected only this far (in angle) past edge-on.
constexpr double kConeMarginRadians = 2.0 * 3.14159265358979 / 180.0;

// Whether every point of `box` (mesh space) is strictly outside one plane the outcodes test
// (x < -w, x > w, y < -w, y > w, z < -w, z > w), with a margin for float rounding.
bool outsideFrustum(const Bounds& box, const float4x4& mvp) {
  if (box.empty()) return true;  // no vertex a triangle could draw with
  // For each plane, the largest signed value over the corners (negative: outside) and the
  // magnitude of the terms.
  double worst[6], magnitude[6];
  std::fill(worst, worst + 6, -INFINITY);
  std::fill(magnitude, magnitude + 6, 0.0);
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
    // Inside plane i when value >= 0: w + x, w - x, w + y, w - y, w + z, w - z.
    const double value[6] = {c[3] + c[0], c[3] - c[0], c[3] + c[1],
                             c[3] - c[1], c[3] + c[2], c[3] - c[2]};
    const int axis[6] = {0, 0, 1, 1, 2, 2};
    for (int i = 0; i < 6; ++i) {
      worst[i] = std::max(worst[i], value[i]);
      magnitude[i] = std::max(magnitude[i], m[3] + m[axis[i]]);
    }
  }
  for (int i = 0; i < 6; ++i) {
    if (!std::isfinite(worst[i]) || !std::isfinite(magnitude[i])) return false;
    if (worst[i] < -kPlaneMargin * magnitude[i]) return true;
  }
  return false;
}

// Where the faces are seen from, in a mesh's space: an eye point (perspective) or a view
// direction (orthographic). `sign` folds in the mirroring of the model matrix and which faces
// are culled.
struct Viewpoint {
  bool valid = false;
  bool directional = false;
  double p[3] = {0, 0, 0};  // the eye, or the direction the camera looks along
};

// True when every triangle of the cluster faces away by the margin: for every point of its
// bounding sphere the view vector is within 90 - alpha - margin degrees of the (signed) axis.
bool facesAway(const MeshCluster& cluster, const Viewpoint& eye, double sign) {
  if (!eye.valid || !(cluster.cone_cos > 0.0f) || cluster.bounds.empty()) return false;
  const double cos_a = cluster.cone_cos, sin_a = std::sqrt(std::max(0.0, 1 - cos_a * cos_a));
  const double s = sin_a * std::cos(kConeMarginRadians) + cos_a * std::sin(kConeMarginRadians);
  if (!(s < 1.0)) return false;
  const double axis[3] = {sign * cluster.cone_axis.x, sign * cluster.cone_axis.y,
                          sign * cluster.cone_axis.z};
  if (eye.directional) {
    const double len = std::sqrt(eye.p[0] * eye.p[0] + eye.p[1] * eye.p[1] + eye.p[2] * eye.p[2]);
    const double d = eye.p[0] * axis[0] + eye.p[1] * axis[1] + eye.p[2] * axis[2];
    return len > 0 && d >= s * len;
  }
  const float3 c = cluster.bounds.center();
  const double r = 0.5 * std::sqrt(double(cluster.bounds.extent().x) * cluster.bounds.extent().x +
                                   double(cluster.bounds.extent().y) * cluster.bounds.extent().y +
                                   double(cluster.bounds.extent().z) * cluster.bounds.extent().z);
  const double v[3] = {c.x - eye.p[0], c.y - eye.p[1], c.z - eye.p[2]};
  const double dist = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  const double along = v[0] * axis[0] + v[1] * axis[1] + v[2] * axis[2];
  return std::isfinite(dist) && along - r > 0 && along - r >= (dist + r) * s;
}

// The camera's eye (or direction) in the mesh's space, when the projection is one whose
// screen-space winding the cone test predicts (a perspective or orthographic row 3).
Viewpoint viewpointIn(const float4x4& inverse_model, const float4x4& inverse_view,
                      const float4x4& projection) {
  Viewpoint out;
  const bool perspective = projection(3, 0) == 0 && projection(3, 1) == 0 &&
                           projection(3, 2) == -1 && projection(3, 3) == 0;
  const bool orthographic = projection(3, 0) == 0 && projection(3, 1) == 0 &&
                            projection(3, 2) == 0 && projection(3, 3) == 1;
  if (!perspective && !orthographic) return out;
  const float4 world = orthographic ? inverse_view * float4{0, 0, -1, 0}
                                    : inverse_view * float4{0, 0, 0, 1};
  const float4 local = inverse_model * world;
  if (!isFinite(local.xyz())) return out;
  out.valid = true;
  out.directional = orthographic;
  out.p[0] = local.x, out.p[1] = local.y, out.p[2] = local.z;
  return out;
}

}  // namespace

void FrustumCull::run(const Scene& scene, const float4x4& view, const float4x4& projection,
                      bool enabled, const std::vector<ObjectTransforms>& objects) {
  triangles_.clear();
  vertices_.clear();
  first_triangle_range_.assign(1, 0);
  first_vertex_range_.assign(1, 0);
  counters_ = {};
  const float4x4 inverse_view = inverse(view);
  for (size_t o = 0; o < scene.objects.size(); ++o) {
    const Object& object = scene.objects[o];
    const size_t base = objects[o].triangle_base;
    const float4x4& mvp = objects[o].model_view_projection;
    const size_t triangle_count = object.mesh ? object.mesh->triangleCount() : 0;
    const size_t vertex_count = object.mesh ? object.mesh->vertexCount() : 0;
    const MeshClusters* clusters = object.clusters.get();
    if (!enabled || !clusters || !object.mesh || !clusters->describes(*object.mesh)) {
      if (triangle_count > 0) triangles_.push_back({base, base + triangle_count});
      if (vertex_count > 0) vertices_.push_back({0, vertex_count});
    } else if (outsideFrustum(clusters->bounds, mvp)) {
      ++counters_.instances_culled;
      counters_.triangles_in_culled_instances += triangle_count;
    } else {
      const bool culls = object.cull != CullMode::kNone;
      const float det = determinant(upper3x3(objects[o].model));
      const double sign = (det < 0 ? -1.0 : 1.0) * (object.cull == CullMode::kFront ? -1.0 : 1.0);
      const Viewpoint eye =
          culls ? viewpointIn(inverse(objects[o].model), inverse_view, projection) : Viewpoint{};
      const size_t vertex_start = vertices_.size();
      for (const MeshCluster& cluster : clusters->clusters) {
        const bool outside = outsideFrustum(cluster.bounds, mvp);
        const bool away = !outside && culls && facesAway(cluster, eye, sign);
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
  }
}

}  // namespace tessera::render
