// MikkTSpace tangents (tangents.h): our implementation of the algorithm as Mikkelsen's thesis
// ("Simulation of wrinkled surfaces revisited", 2008) and mikktspace.h describe it. The rules it
// follows, in its order:
//  1. Vertices are welded by value: corners whose position, normal and UV are equal (bit for bit,
//     -0 = +0) are one vertex for the algorithm, whatever their indices (exporters split vertices
//     for other attributes, and MikkTSpace never sees indices).
//  2. A triangle with two corners on one welded vertex is degenerate and takes no part in the
//     grouping; so is one with non-finite data.
//  3. Each triangle's dP/du and dP/dv from its positions and UVs, normalised (magnitudes play no
//     part in a unit tangent); the sign of its UV determinant is its orientation. A triangle with
//     zero UV area or a zero dP/du or dP/dv has no gradient of its own ("group with any"): it
//     joins the first group that reaches it and takes that group's orientation.
//  4. Groups: around each welded vertex, the triangles of one orientation connected through
//     shared edges (between welded vertices, walked in opposite directions) share a tangent.
//  5. A group's tangent: the sum over its triangles with a gradient of dP/du projected across the
//     corner's normal and normalised, weighted by the corner's angle (between its two edges
//     projected the same way); then normalised. Its sign: +1 for a positive orientation, else -1.
//  6. Corners of degenerate triangles take the tangent of the first grouped corner on the same
//     welded vertex (in triangle order).
// Left out: the sub-groups (MikkTSpace parts a group whose triangles' projected tangents are "not
// alike"; at its default threshold of 180 degrees that parts only exactly opposite directions),
// quads (the mesh holds triangles), the bitangent and the magnitudes (Mesh holds a unit tangent
// and a sign). Deviation: corners no group reaches take the tangent of the first grouped corner on
// their vertex as degenerate ones do, else that of a group their triangle joined at another
// corner (a zero-UV-area triangle's far corner); MikkTSpace gives them (1, 0, 0). Where there is
// none of these, fallbackTangent.
//
// One vertex of the mesh can end up with corners in different groups (a mirrored UV seam whose
// two sides share vertices): it is split, a copy per distinct tangent, and the corners' indices
// point at their copies.
#include <tessera/scene/tangents.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cfloat>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <vector>

namespace tessera {
namespace {

constexpr uint32_t kNone = std::numeric_limits<uint32_t>::max();

// Mesh's arrays: six per vertex (copyVertex copies each) and three per triangle. A new
// per-vertex array (morph targets, joints and weights) must be copied there too.
static_assert(sizeof(Mesh) == 9 * sizeof(std::vector<float>),
              "a new Mesh array: if it is per vertex, copyVertex must copy it");

// MikkTSpace's test for "not zero".
bool notZero(float x) {
  return std::fabs(x) > FLT_MIN;
}

// `x` at unit length, or zero: the direct path when its squared length is a normal float (most
// calls), safeNormalize (which rescales) for huge, tiny or non-finite ones.
float3 unitOrZero(float3 x) {
  const float length2 = dot(x, x);
  if (length2 > FLT_MIN && length2 < FLT_MAX) return x * (1.0f / std::sqrt(length2));
  return safeNormalize(x);
}

// `x` projected across the unit normal `n`, normalised; a zero vector stays zero.
float3 acrossNormal(float3 x, float3 n) {
  return unitOrZero(x - n * dot(n, x));
}

// A unit tangent where no UV gradient gives one: +x across the normal, else +y.
float3 fallbackTangent(float3 n) {
  const float3 t = acrossNormal(float3{1, 0, 0}, n);
  return length(t) > 0.5f ? t : acrossNormal(float3{0, 1, 0}, n);
}

struct Triangle {
  size_t first_index = 0;            // into Mesh::indices
  std::array<uint32_t, 3> vertex{};  // the mesh's
  std::array<uint32_t, 3> welded{};
  std::array<uint32_t, 3> neighbour{kNone, kNone, kNone};  // across the edge corner k -> k + 1
  std::array<uint32_t, 3> group{kNone, kNone, kNone};
  float3 tangent{};         // unit dP/du, or zero
  bool positive = true;     // orientation: the UV determinant is positive
  bool gradient = false;    // has unit dP/du and dP/dv of its own
  bool degenerate = false;  // two corners on one welded vertex, or non-finite data

  int cornerOf(uint32_t welded_vertex) const {
    return welded[0] == welded_vertex ? 0 : welded[1] == welded_vertex ? 1 : 2;
  }
  bool grouped() const { return group[0] != kNone || group[1] != kNone || group[2] != kNone; }
};

struct Group {
  uint32_t welded;
  bool positive;
  float3 sum{};  // angle-weighted projected tangents
};

struct Work {
  const Mesh& mesh;
  std::vector<Triangle> triangles;
  std::vector<Group> groups;
  std::vector<float3> normals;  // unit (or zero) per vertex, selected ones only
};

using WeldKey = std::array<uint32_t, 8>;

WeldKey weldKey(const Mesh& mesh, uint32_t v) {
  const float values[8] = {mesh.positions[v].x, mesh.positions[v].y, mesh.positions[v].z,
                           mesh.normals[v].x,   mesh.normals[v].y,   mesh.normals[v].z,
                           mesh.uvs[v].x,       mesh.uvs[v].y};
  WeldKey key;
  for (int i = 0; i < 8; ++i) {
    const float value = values[i] == 0.0f ? 0.0f : values[i];  // -0 welds with +0
    std::memcpy(&key[i], &value, sizeof(float));
  }
  return key;
}

uint64_t hashKey(const WeldKey& key) {
  uint64_t h = 0x9e3779b97f4a7c15ull;
  for (uint32_t word : key) {
    h = (h ^ word) * 0xff51afd7ed558ccdull;
    h ^= h >> 32;
  }
  return h;
}

struct Welding {
  std::vector<uint32_t> id;  // per vertex of the mesh; kNone for those not selected
  size_t count = 0;          // distinct ids
};

// Rule 1: one id per distinct key among the selected vertices (an open-addressing hash table of
// representatives: linear in the vertex count).
Welding weldVertices(const Mesh& mesh, const std::vector<uint8_t>& selected) {
  const size_t selected_count =
      static_cast<size_t>(std::count(selected.begin(), selected.end(), 1));
  const size_t capacity = std::bit_ceil(std::max<size_t>(16, 2 * selected_count));
  std::vector<uint32_t> representative(capacity, kNone);
  Welding welding;
  welding.id.assign(selected.size(), kNone);
  for (size_t v = 0; v < selected.size(); ++v) {
    if (!selected[v]) continue;
    const WeldKey key = weldKey(mesh, static_cast<uint32_t>(v));
    size_t slot = hashKey(key) & (capacity - 1);
    while (representative[slot] != kNone && weldKey(mesh, representative[slot]) != key)
      slot = (slot + 1) & (capacity - 1);
    if (representative[slot] == kNone) {
      representative[slot] = static_cast<uint32_t>(v);
      welding.id[v] = static_cast<uint32_t>(welding.count++);
    } else {
      welding.id[v] = welding.id[representative[slot]];
    }
  }
  return welding;
}

// Rule 3: the triangle's unit dP/du, its orientation and whether it has a gradient.
void triangleGradient(const Mesh& mesh, Triangle& t) {
  const float3 p0 = mesh.positions[t.vertex[0]];
  const float3 d1 = mesh.positions[t.vertex[1]] - p0, d2 = mesh.positions[t.vertex[2]] - p0;
  const float2 uv0 = mesh.uvs[t.vertex[0]];
  const float2 s1 = mesh.uvs[t.vertex[1]] - uv0, s2 = mesh.uvs[t.vertex[2]] - uv0;
  const float det = s1.x * s2.y - s1.y * s2.x;
  t.positive = det > 0.0f;
  if (!notZero(det)) return;
  // dP/du and dP/dv times det (Cramer's rule on d1 = Pu s1.x + Pv s1.y, d2 = Pu s2.x + Pv s2.y).
  const float sign = t.positive ? 1.0f : -1.0f;
  t.tangent = unitOrZero((d1 * s2.y - d2 * s1.y) * sign);
  const float3 bitangent = unitOrZero((d2 * s1.x - d1 * s2.x) * sign);
  t.gradient = length(t.tangent) > 0.0f && length(bitangent) > 0.0f;
}

bool finiteCorner(const Mesh& mesh, uint32_t v) {
  return isFinite(mesh.positions[v]) && isFinite(mesh.normals[v]) && std::isfinite(mesh.uvs[v].x) &&
         std::isfinite(mesh.uvs[v].y);
}

// The triangles whose corners are all selected, with their welded vertices and gradients.
std::vector<Triangle> selectTriangles(const Mesh& mesh, const std::vector<uint8_t>& selected,
                                      const std::vector<uint32_t>& welded) {
  std::vector<Triangle> triangles;
  triangles.reserve(mesh.triangleCount());
  const size_t count = mesh.vertexCount();
  for (size_t i = 0; i + 2 < mesh.indices.size(); i += 3) {
    Triangle t;
    t.first_index = i;
    bool usable = true, finite = true;
    for (int k = 0; k < 3; ++k) {
      t.vertex[k] = mesh.indices[i + k];
      usable = usable && t.vertex[k] < count && selected[t.vertex[k]];
      if (!usable) break;
      t.welded[k] = welded[t.vertex[k]];
      finite = finite && finiteCorner(mesh, t.vertex[k]);
    }
    if (!usable) continue;
    t.degenerate = !finite || t.welded[0] == t.welded[1] || t.welded[1] == t.welded[2] ||
                   t.welded[2] == t.welded[0];
    if (!t.degenerate) triangleGradient(mesh, t);
    triangles.push_back(t);
  }
  return triangles;
}

// Rule 4's adjacency: an edge's neighbour is a triangle walking it the other way. Where more
// than two triangles share an edge, they pair up in triangle order.
void linkNeighbours(std::vector<Triangle>& triangles, size_t welded_count) {
  // Edge ends bucketed by their lower welded vertex (a counting sort), each as (higher vertex,
  // 3 x triangle + corner); a bucket holds about twice the valence.
  std::vector<size_t> first(welded_count + 1, 0);
  for (const Triangle& t : triangles)
    if (!t.degenerate)
      for (int k = 0; k < 3; ++k) ++first[std::min(t.welded[k], t.welded[(k + 1) % 3]) + 1];
  for (size_t w = 0; w < welded_count; ++w) first[w + 1] += first[w];
  std::vector<std::pair<uint32_t, uint32_t>> ends(first.back());
  std::vector<size_t> next(first.begin(), first.end() - 1);
  for (size_t i = 0; i < triangles.size(); ++i) {
    const Triangle& t = triangles[i];
    if (t.degenerate) continue;
    for (uint32_t k = 0; k < 3; ++k) {
      const uint32_t a = t.welded[k], b = t.welded[(k + 1) % 3];
      ends[next[std::min(a, b)]++] = {std::max(a, b), static_cast<uint32_t>(3 * i + k)};
    }
  }
  auto forward = [&](uint32_t end) {
    const Triangle& t = triangles[end / 3];
    return t.welded[end % 3] < t.welded[(end % 3 + 1) % 3];
  };
  for (size_t w = 0; w < welded_count; ++w) {
    const auto bucket_begin = ends.begin() + static_cast<std::ptrdiff_t>(first[w]);
    const auto bucket_end = ends.begin() + static_cast<std::ptrdiff_t>(first[w + 1]);
    std::sort(bucket_begin, bucket_end);
    // Per edge (equal higher vertex), the n-th end walking it up pairs with the n-th walking down.
    for (auto run = bucket_begin; run != bucket_end;) {
      auto run_end = run;
      while (run_end != bucket_end && run_end->first == run->first) ++run_end;
      auto f = run, b = run;
      while (true) {
        while (f != run_end && !forward(f->second)) ++f;
        while (b != run_end && forward(b->second)) ++b;
        if (f == run_end || b == run_end) break;
        triangles[f->second / 3].neighbour[f->second % 3] = b->second / 3;
        triangles[b->second / 3].neighbour[b->second % 3] = f->second / 3;
        ++f, ++b;
      }
      run = run_end;
    }
  }
}

// Rule 4: group `g` spreads from `seed` to the triangles around its vertex through shared edges,
// depth first (the order decides the orientation of triangles without a gradient, as in
// MikkTSpace).
void spreadGroup(Work& work, uint32_t seed, uint32_t g, std::vector<uint32_t>& stack) {
  const Group group = work.groups[g];
  stack.assign(1, seed);
  while (!stack.empty()) {
    Triangle& t = work.triangles[stack.back()];
    stack.pop_back();
    const int i = t.cornerOf(group.welded);
    if (t.group[i] != kNone) continue;
    if (!t.gradient && !t.grouped()) t.positive = group.positive;
    if (t.positive != group.positive) continue;
    t.group[i] = g;
    // Both edges at corner i; the one leaving it is walked first.
    for (const uint32_t next : {t.neighbour[(i + 2) % 3], t.neighbour[i]})
      if (next != kNone) stack.push_back(next);
  }
}

void buildGroups(Work& work) {
  std::vector<uint32_t> stack;
  for (size_t i = 0; i < work.triangles.size(); ++i) {
    for (int k = 0; k < 3; ++k) {
      const Triangle& t = work.triangles[i];
      if (t.degenerate || !t.gradient || t.group[k] != kNone) continue;
      work.groups.push_back({t.welded[k], t.positive});
      spreadGroup(work, static_cast<uint32_t>(i), static_cast<uint32_t>(work.groups.size() - 1),
                  stack);
    }
  }
}

// Rule 5: each grouped corner with a gradient adds its projected tangent, weighted by its angle.
void sumGroups(Work& work) {
  const Mesh& mesh = work.mesh;
  for (const Triangle& t : work.triangles) {
    if (!t.gradient) continue;
    for (int i = 0; i < 3; ++i) {
      if (t.group[i] == kNone) continue;
      const float3 n = work.normals[t.vertex[i]];
      const float3 p = mesh.positions[t.vertex[i]];
      const float3 e1 = acrossNormal(mesh.positions[t.vertex[(i + 2) % 3]] - p, n);
      const float3 e2 = acrossNormal(mesh.positions[t.vertex[(i + 1) % 3]] - p, n);
      const float angle = std::acos(std::clamp(dot(e1, e2), -1.0f, 1.0f));
      work.groups[t.group[i]].sum += acrossNormal(t.tangent, n) * angle;
    }
  }
}

// Every corner's tangent and sign (rules 5 and 6, and the fallback), worked out as they are
// written (no array of corners: a large mesh's would be its largest allocation).
class CornerTangents {
 public:
  CornerTangents(const Work& work, size_t welded_count) : work_(work) {
    group_tangent_.resize(work.groups.size());
    for (size_t g = 0; g < work.groups.size(); ++g) {
      const float3 t = unitOrZero(work.groups[g].sum);  // zero: replaced in of()
      group_tangent_[g] = float4(t, work.groups[g].positive ? 1.0f : -1.0f);
    }
    first_group_.assign(welded_count, kNone);
    for (const Triangle& t : work.triangles)
      for (int i = 0; i < 3; ++i)
        if (t.group[i] != kNone && first_group_[t.welded[i]] == kNone)
          first_group_[t.welded[i]] = t.group[i];
  }

  float4 of(const Triangle& t, int i, TangentReport& report) const {
    uint32_t g = t.group[i];
    if (g == kNone) g = first_group_[t.welded[i]];
    for (int k = 0; k < 3 && g == kNone; ++k) g = t.group[k];  // the triangle's own group
    const float4 value = g == kNone ? float4{0, 0, 0, 1} : group_tangent_[g];
    if (length(value.xyz()) > 0.0f) return value;
    // No group, or its tangents cancelled out.
    ++report.fallback_corners;
    return float4(fallbackTangent(work_.normals[t.vertex[i]]), value.w);
  }

 private:
  const Work& work_;
  std::vector<float4> group_tangent_;
  std::vector<uint32_t> first_group_;  // per welded vertex: its first corner's group
};

// A copy of vertex `v` at the end of every per-vertex array, with tangent `tangent`.
uint32_t copyVertex(Mesh& mesh, uint32_t v, float4 tangent) {
  const auto copy = static_cast<uint32_t>(mesh.positions.size());
  const bool colored = mesh.colors.size() == mesh.positions.size();
  const bool second_set = mesh.uvs1.size() == mesh.positions.size();
  const float3 position = mesh.positions[v], normal = mesh.normals[v];
  const float2 uv = mesh.uvs[v];
  mesh.positions.push_back(position);
  mesh.normals.push_back(normal);
  mesh.uvs.push_back(uv);
  if (second_set) {
    const float2 uv1 = mesh.uvs1[v];
    mesh.uvs1.push_back(uv1);
  }
  if (colored) {
    const float4 color = mesh.colors[v];
    mesh.colors.push_back(color);
  }
  mesh.tangents.push_back(tangent);
  return copy;
}

// Writes the corners' tangents to their vertices; a vertex whose corners disagree is split.
void writeTangents(Mesh& mesh, const std::vector<Triangle>& triangles,
                   const CornerTangents& corners, TangentReport& report) {
  std::vector<uint8_t> claimed(mesh.vertexCount(), 0);
  std::vector<uint32_t> next_copy(mesh.vertexCount(), kNone);  // the chain of a vertex's copies
  for (size_t j = 0; j < triangles.size(); ++j) {
    for (size_t i = 0; i < 3; ++i) {
      const uint32_t v = triangles[j].vertex[i];
      const float4 value = corners.of(triangles[j], static_cast<int>(i), report);
      if (!claimed[v]) {
        claimed[v] = 1;
        mesh.tangents[v] = value;
        continue;
      }
      uint32_t u = v;
      while (!(mesh.tangents[u] == value) && next_copy[u] != kNone) u = next_copy[u];
      if (!(mesh.tangents[u] == value)) {
        if (mesh.positions.size() >= kNone) continue;  // no index left: the vertex stays shared
        const uint32_t copy = copyVertex(mesh, v, value);
        next_copy.push_back(kNone);
        next_copy[u] = copy;
        u = copy;
        ++report.split_vertices;
      }
      mesh.indices[triangles[j].first_index + i] = u;
    }
  }
}

TangentReport generateSelected(Mesh& mesh, const std::vector<uint8_t>& selected) {
  TangentReport report;
  const Welding welding = weldVertices(mesh, selected);
  Work work{mesh, selectTriangles(mesh, selected, welding.id), {}, {}};
  work.normals.resize(mesh.vertexCount());
  for (size_t v = 0; v < mesh.vertexCount(); ++v)
    if (selected[v]) {
      const float3 n = mesh.normals[v];
      work.normals[v] = isFinite(n) ? safeNormalize(n) : float3{0, 0, 0};
      // Selected vertices no triangle uses keep this.
      mesh.tangents[v] = float4(fallbackTangent(work.normals[v]), 1.0f);
    }
  linkNeighbours(work.triangles, welding.count);
  buildGroups(work);
  sumGroups(work);
  const CornerTangents corners(work, welding.count);
  writeTangents(mesh, work.triangles, corners, report);
  return report;
}

bool hasNormalsAndUvs(const Mesh& mesh) {
  return mesh.normals.size() == mesh.vertexCount() && mesh.uvs.size() == mesh.vertexCount();
}

// Set 1 as Mesh::uvs while it lives (the algorithm reads uvs; copyVertex copies both sets).
class UvSetSwap {
 public:
  UvSetSwap(Mesh& mesh, int uv_set)
      : mesh_(mesh), swapped_(uv_set == 1 && mesh.uvs1.size() == mesh.vertexCount()) {
    if (swapped_) std::swap(mesh_.uvs, mesh_.uvs1);
  }
  ~UvSetSwap() {
    if (swapped_) std::swap(mesh_.uvs, mesh_.uvs1);
  }
  UvSetSwap(const UvSetSwap&) = delete;
  UvSetSwap& operator=(const UvSetSwap&) = delete;

 private:
  Mesh& mesh_;
  bool swapped_;
};

}  // namespace

TangentReport generateTangents(Mesh& mesh, int uv_set) {
  const UvSetSwap set(mesh, uv_set);
  if (!hasNormalsAndUvs(mesh)) {
    mesh.tangents.clear();
    return {};
  }
  mesh.tangents.assign(mesh.vertexCount(), float4{1, 0, 0, 1});
  return generateSelected(mesh, std::vector<uint8_t>(mesh.vertexCount(), 1));
}

TangentReport generateTangents(Mesh& mesh, std::span<const VertexRange> ranges, int uv_set) {
  const UvSetSwap set(mesh, uv_set);
  if (!hasNormalsAndUvs(mesh)) {
    mesh.tangents.clear();
    return {};
  }
  mesh.tangents.resize(mesh.vertexCount(), float4{1, 0, 0, 1});
  std::vector<uint8_t> selected(mesh.vertexCount(), 0);
  for (const auto& [first, end] : ranges)
    for (size_t v = first; v < std::min(end, mesh.vertexCount()); ++v) selected[v] = 1;
  return generateSelected(mesh, selected);
}

}  // namespace tessera
