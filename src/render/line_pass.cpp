#include "render/line_pass.h"

#include <algorithm>
#include <bit>
#include <tuple>

#include <tessera/math/mat.h>

#include "render/lines.h"

namespace tessera::render {

void EdgeLines::collect(const Mesh& mesh) {
  const size_t vertex_count = mesh.vertexCount();
  // Vertices at one position (a flat-shaded cube's corner, say, three times) are one: bitwise,
  // so the order is total and the result does not depend on the sort.
  auto bits = [&](uint32_t v) {
    const float3 p = mesh.positions[v];
    return std::make_tuple(std::bit_cast<uint32_t>(p.x), std::bit_cast<uint32_t>(p.y),
                           std::bit_cast<uint32_t>(p.z), v);
  };
  by_position_.resize(vertex_count);
  for (size_t v = 0; v < vertex_count; ++v) by_position_[v] = static_cast<uint32_t>(v);
  std::sort(by_position_.begin(), by_position_.end(),
            [&](uint32_t a, uint32_t b) { return bits(a) < bits(b); });
  canonical_.resize(vertex_count);
  for (size_t i = 0; i < vertex_count; ++i) {
    const uint32_t v = by_position_[i];
    const bool same = i > 0 && std::get<0>(bits(v)) == std::get<0>(bits(by_position_[i - 1])) &&
                      std::get<1>(bits(v)) == std::get<1>(bits(by_position_[i - 1])) &&
                      std::get<2>(bits(v)) == std::get<2>(bits(by_position_[i - 1]));
    canonical_[v] = same ? canonical_[by_position_[i - 1]] : v;
  }

  edges_.clear();
  const size_t triangle_count = mesh.triangleCount();
  const bool flagged = mesh.triangle_edges.size() == triangle_count;
  for (size_t t = 0; t < triangle_count; ++t) {
    const uint32_t* idx = &mesh.indices[t * 3];
    if (idx[0] >= vertex_count || idx[1] >= vertex_count || idx[2] >= vertex_count) continue;
    const uint8_t outline = flagged ? mesh.triangle_edges[t] : kAllTriangleEdges;
    for (int k = 0; k < 3; ++k) {
      if (!(outline & (1u << k))) continue;
      const uint32_t a = canonical_[idx[k]], b = canonical_[idx[(k + 1) % 3]];
      if (a == b) continue;
      edges_.push_back(uint64_t{std::min(a, b)} << 32 | std::max(a, b));
    }
  }
  std::sort(edges_.begin(), edges_.end());
  edges_.erase(std::unique(edges_.begin(), edges_.end()), edges_.end());
}

void EdgeLines::build(const Scene& scene, const std::vector<ObjectTransforms>& objects,
                      float3 color, LineList& lines) {
  lines.points.clear();
  lines.colors.clear();
  for (size_t i = 0; i < scene.objects.size(); ++i) {
    const Mesh* mesh = scene.objects[i].mesh.get();
    if (!mesh) continue;
    collect(*mesh);
    const float4x4& model = objects[i].model;
    for (uint64_t edge : edges_) {
      const float3 a = mesh->positions[edge >> 32], b = mesh->positions[edge & 0xffffffffu];
      lines.add((model * float4{a, 1.0f}).xyz(), (model * float4{b, 1.0f}).xyz(), color);
    }
  }
}

void axisLines(const Scene& scene, const std::vector<ObjectTransforms>& objects, LineList& lines) {
  lines.points.clear();
  lines.colors.clear();
  if (scene.show_world_axes) appendAxes(lines, float4x4::identity(), scene.world_axes_length);
  for (size_t i = 0; i < scene.objects.size(); ++i)
    if (scene.objects[i].show_axes)
      appendAxes(lines, objects[i].model, scene.objects[i].axes_length);
}

bool LinePass::wanted(const Scene& scene, const RenderOptions& options) {
  return options.lines &&
         (!scene.lines.points.empty() || scene.show_world_axes || options.edges.show ||
          std::any_of(scene.objects.begin(), scene.objects.end(),
                      [](const Object& o) { return o.show_axes; }));
}

void LinePass::draw(const Scene& scene, const std::vector<ObjectTransforms>& objects,
                    const RenderOptions& options, const float4x4& view_projection, bool antialiased,
                    Frame& frame) {
  drawLines(scene.lines, view_projection, frame, antialiased, LineStyle{options.line_width});
  axisLines(scene, objects, axes_);
  drawLines(axes_, view_projection, frame, antialiased);
  if (!options.edges.show) return;
  edges_.build(scene, objects, options.edges.color, edge_lines_);
  const LineStyle style{options.edges.width, kEdgeDepthPull,
                        (inverse(scene.camera.view()) * float4{0, 0, 0, 1}).xyz()};
  drawLines(edge_lines_, view_projection, frame, antialiased, style);
}

}  // namespace tessera::render
