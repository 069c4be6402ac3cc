#include <tessera/scene/clusters.h>

#include <algorithm>
#include <cmath>
#include <utility>

namespace tessera {

namespace {

// The cone of one cluster's face normals: the axis is their normalized sum, the half-angle the
// widest normal's. Computed in double: the test must hold for every triangle, and the renderer
// adds its own margin on top.
void fitCone(const Mesh& mesh, MeshCluster& cluster) {
  double min_altitude = INFINITY, min_edge = INFINITY;
  const auto normalOf = [&](uint32_t t, double n[3]) {
    const uint32_t* idx = &mesh.indices[size_t{t} * 3];
    const float3 a = mesh.positions[idx[0]], b = mesh.positions[idx[1]], c = mesh.positions[idx[2]];
    const double e1[3] = {double(b.x) - a.x, double(b.y) - a.y, double(b.z) - a.z};
    const double e2[3] = {double(c.x) - a.x, double(c.y) - a.y, double(c.z) - a.z};
    n[0] = e1[1] * e2[2] - e1[2] * e2[1];
    n[1] = e1[2] * e2[0] - e1[0] * e2[2];
    n[2] = e1[0] * e2[1] - e1[1] * e2[0];
    const double len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    if (!(len > 0) || !std::isfinite(len)) return false;
    const double e3[3] = {e2[0] - e1[0], e2[1] - e1[1], e2[2] - e1[2]};
    const double l1 = std::sqrt(e1[0] * e1[0] + e1[1] * e1[1] + e1[2] * e1[2]);
    const double l2 = std::sqrt(e2[0] * e2[0] + e2[1] * e2[1] + e2[2] * e2[2]);
    const double l3 = std::sqrt(e3[0] * e3[0] + e3[1] * e3[1] + e3[2] * e3[2]);
    min_altitude = std::min(min_altitude, len / std::max({l1, l2, l3}));
    min_edge = std::min({min_edge, l1, l2, l3});
    for (int i = 0; i < 3; ++i) n[i] /= len;
    return true;
  };
  const size_t vertex_count = mesh.vertexCount();
  const auto usable = [&](uint32_t t) {
    const uint32_t* idx = &mesh.indices[size_t{t} * 3];
    return idx[0] < vertex_count && idx[1] < vertex_count && idx[2] < vertex_count &&
           isFinite(mesh.positions[idx[0]]) && isFinite(mesh.positions[idx[1]]) &&
           isFinite(mesh.positions[idx[2]]);
  };
  double sum[3] = {0, 0, 0};
  const uint32_t end = cluster.first_triangle + cluster.triangle_count;
  for (uint32_t t = cluster.first_triangle; t < end; ++t) {
    double n[3];
    if (!usable(t)) continue;
    // A degenerate triangle can gain an area when the rasterizer snaps it: no cone.
    if (!normalOf(t, n)) return;
    for (int i = 0; i < 3; ++i) sum[i] += n[i];
  }
  const double len = std::sqrt(sum[0] * sum[0] + sum[1] * sum[1] + sum[2] * sum[2]);
  if (!(len > 1e-9)) return;
  for (double& v : sum) v /= len;
  double min_cos = 1.0;
  for (uint32_t t = cluster.first_triangle; t < end; ++t) {
    double n[3];
    if (!usable(t) || !normalOf(t, n)) continue;
    min_cos = std::min(min_cos, n[0] * sum[0] + n[1] * sum[1] + n[2] * sum[2]);
  }
  cluster.cone_axis = {static_cast<float>(sum[0]), static_cast<float>(sum[1]),
                       static_cast<float>(sum[2])};
  // Widened by more than the float rounding of the axis and the cosine.
  cluster.cone_cos = static_cast<float>(min_cos - 1e-5);
  // Rounded down, so that the renderer's bound stays a bound.
  cluster.min_altitude = static_cast<float>(min_altitude * (1.0 - 1e-6));
  cluster.min_edge = static_cast<float>(min_edge * (1.0 - 1e-6));
  if (!(cluster.min_altitude > 0.0f) || !(cluster.min_edge > 0.0f)) cluster.cone_cos = -1.0f;
}

}  // namespace

std::shared_ptr<const MeshClusters> buildClusters(const Mesh& mesh) {
  auto out = std::make_shared<MeshClusters>();
  out->vertex_count = mesh.vertexCount();
  out->triangle_count = mesh.triangleCount();
  const size_t vertex_count = mesh.vertexCount();
  for (size_t first = 0; first < out->triangle_count; first += kClusterTriangles) {
    MeshCluster cluster;
    cluster.first_triangle = static_cast<uint32_t>(first);
    cluster.triangle_count =
        static_cast<uint32_t>(std::min<size_t>(kClusterTriangles, out->triangle_count - first));
    uint32_t lo = UINT32_MAX, hi = 0;
    for (size_t i = first * 3; i < (first + cluster.triangle_count) * 3; ++i) {
      const uint32_t v = mesh.indices[i];
      if (v >= vertex_count) continue;
      lo = std::min(lo, v);
      hi = std::max(hi, v);
      if (isFinite(mesh.positions[v]))
        cluster.bounds.add(mesh.positions[v]);
      else
        out->finite = false;
    }
    cluster.first_vertex = lo == UINT32_MAX ? 0 : lo;
    cluster.end_vertex = lo == UINT32_MAX ? 0 : hi + 1;
    fitCone(mesh, cluster);
    if (!cluster.bounds.empty()) {
      out->bounds.add(cluster.bounds.min);
      out->bounds.add(cluster.bounds.max);
    }
    out->clusters.push_back(cluster);
  }
  return out;
}

Mesh reversedWinding(const Mesh& mesh) {
  Mesh out = mesh;
  for (size_t i = 0; i + 2 < out.indices.size(); i += 3)
    std::swap(out.indices[i + 1], out.indices[i + 2]);
  return out;
}

}  // namespace tessera
