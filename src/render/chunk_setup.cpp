// The setup stage of the CPU backend, one chunk of triangles at a time: assembly, culling (eight
// triangles at a time through the cull kernel), clipping, setup of the raster and shading records
// (eight at a time through the setup kernel) and binning to tiles, in submission order.
#include <algorithm>
#if defined(__SSE2__)
#include <immintrin.h>
#endif

#include <tessera/base/check.h>

#include "render/blend.h"
#include "render/clip.h"
#include "render/cpu_renderer_state.h"
#include "render/fixed_point.h"

namespace tessera {

using namespace render;

void CpuRenderer::State::setupChunk(const Scene& scene, const VertexBuffer& vertices,
                                    const TileGrid& grid, const GuardBand& guard, bool want_normals,
                                    int32_t sample_reach, TriangleChunk& chunk) const {
  chunk.size = 0;
  chunk.bins.reset(grid.tileCount(), pool.size() > 1);
  chunk.culled = 0;
  chunk.clipped = 0;
  chunk.cull_reasons = {};
  chunk.clip_splits = 0;
  chunk.any_masked = false;
  chunk.blended.clear();

  const size_t begin = chunk.first_triangle, end = begin + chunk.triangle_count;
  size_t object_index = objectHolding(objects, begin);

  TriangleOrientation orientation;
  // The record slot of the next visible triangle: setup writes in place, and the slot counts
  // (chunk.size) only once the triangle survives.
  auto nextRecord = [&] {
    const uint32_t local = static_cast<uint32_t>(chunk.size);
    TESSERA_CHECK(local < kMaxTrianglesPerChunk) << "chunk holds too many triangles";
    if (local == chunk.raster.size()) {
      chunk.raster.emplace_back();
      chunk.wide.emplace_back();
      chunk.shade.emplace_back();
      chunk.extras.emplace_back();
    }
    return local;
  };

  // Unclipped triangles wait here for the rest of their setup (setup_kernel.h). The kernel
  // depends on nothing per object, so one flush per full batch and one at the end of the chunk.
  SetupBatch batch;
  const SetupBatchFn setup_batch = kernels.setup_batch;
  const CullGroupFn cull_group = kernels.cull_group;
  auto flush = [&] {
    if (batch.count == 0) return;
    batch.padLanes();
    setup_batch(batch, grid.width, grid.height, sample_reach, chunk.raster.data(),
                chunk.wide.data(), chunk.shade.data());
    batch.count = 0;
  };

  const float width = static_cast<float>(grid.width), height = static_cast<float>(grid.height);
  for (size_t t = begin; t < end; ++object_index) {
    const Object& object = scene.objects[object_index];
    const ObjectTransforms& xf = objects[object_index];
    const size_t object_end = xf.triangle_base + (object.mesh ? object.mesh->triangleCount() : 0);
    if (!object.mesh || t >= object_end) continue;
    if (!cull.drawsTriangles(object_index)) {
      t = std::min(end, object_end);
      continue;
    }
    const Mesh& mesh = *object.mesh;
    const size_t vertex_count = mesh.vertexCount();
    const bool has_uv = mesh.uvs.size() == vertex_count;
    const bool has_color = mesh.colors.size() == vertex_count;
    const bool has_materials = mesh.triangle_materials.size() == mesh.triangleCount();

    const SetupContext ctx = objectSetupContext(lights, object, xf.model, grid.width, grid.height,
                                                want_normals, sample_reach);
    // Flat shading lights the face; so do vertices of a mesh without normals. A mirrored object's
    // triangles compare it with their vertex normals (setup.cpp: the normals' facing).
    const bool needs_face_normal = object.shading == Shading::kFlat ||
                                   mesh.normals.size() != vertex_count || xf.winding_sign < 0.0f;
    const MeshVertices mesh_vertices{
        vertices.screen.data() + xf.vertex_base,
        vertices.normal.data() + xf.vertex_base,
        litPerVertex(object, lights) ? vertices.lit.data() + xf.vertex_base : nullptr,
        has_uv ? mesh.uvs.data() : nullptr,
        has_color ? mesh.colors.data() : nullptr,
        mesh.positions.data(),
        meshUv1(ctx, mesh)};
    const uint16_t* outcodes = vertices.outcode.data() + xf.vertex_base;
    PlainGouraud plain_gouraud = plainGouraudFor(ctx, mesh_vertices, has_materials);
    // A mirrored object's front faces may show their vertex normals' back (setup.cpp).
    if (xf.winding_sign < 0.0f) plain_gouraud.applies = false;

    // Read only for the triangles that survive the cull.
    auto material = [&](size_t local) {
      return has_materials ? mesh.triangle_materials[local] : uint16_t{0};
    };
    // One look at the object's materials. alphaMode MASK: the raster tests such triangles' alpha
    // (rasterMasked), in the chunks that hold one. BLEND: such triangles wait for the transparent
    // pass (blend.h), out of the bins.
    bool any_blended = false;
    for (const Material& m : object.materials) {
      chunk.any_masked |= m.alpha_mode == AlphaMode::kMask;
      any_blended |= isBlended(m);
    }
    auto bin = [&](const auto& box, uint32_t record, const ShadeTriangle& shade)
        __attribute__((always_inline)) {
      if (any_blended && isBlended(*shade.material))
        chunk.blended.push_back(record);
      else
        chunk.bins.add(grid, box, record);
    };
    auto face_normal = [&](const uint32_t idx[3]) {
      if (!needs_face_normal) return float3{};
      const float3 p0 = mesh.positions[idx[0]], p1 = mesh.positions[idx[1]],
                   p2 = mesh.positions[idx[2]];
      return xf.normal_matrix * cross(p1 - p0, p2 - p0) * xf.winding_sign;
    };

    // A triangle that passed the cull whole: binned now, in submission order; the edges and
    // planes come eight at a time (flush).
    auto drawWhole = [&](size_t t, const uint32_t idx[3], int64_t area, const PixelBox& box)
        __attribute__((always_inline)) {
      const size_t local = t - xf.triangle_base;
      const uint32_t id = static_cast<uint32_t>(t);
      const uint32_t record = nextRecord();
      ++chunk.size;
      orient(area, orientation);
      ShadeTriangle& shade = batch.nextShade();
      if (!plainGouraudCorners(ctx, plain_gouraud, mesh_vertices, idx, orientation, id,
                               material(local), shade))
        setupShadeCorners(ctx, mesh_vertices, idx, orientation, face_normal(idx), id,
                          material(local), shade, chunk.extras[record]);
      bin(box, record, shade);
      batch.push(mesh_vertices.screen[idx[0]], mesh_vertices.screen[idx[1]],
                 mesh_vertices.screen[idx[2]], area, record);
      if (batch.full()) flush();
    };

    // A triangle crossing the near or far plane or leaving the guard band: clip, then fan.
    auto drawClipped = [&](size_t t, const uint32_t idx[3], uint32_t cut) {
      const size_t local = t - xf.triangle_base;
      const uint32_t id = static_cast<uint32_t>(t);
      ++chunk.clipped;
      ClipVertex in[3];
      const bool needs_world = needsWorld(lights, object.shading);
      for (int k = 0; k < 3; ++k) {
        in[k] = {vertices.clip(xf.vertex_base + idx[k]), vertices.normal[xf.vertex_base + idx[k]],
                 has_uv ? mesh.uvs[idx[k]] : float2{},
                 has_color ? mesh.colors[idx[k]] : float4{1, 1, 1, 1},
                 needs_world ? (xf.model * float4(mesh.positions[idx[k]], 1.0f)).xyz() : float3{}};
        if (ctx.tangents) {
          const float4 t = ctx.tangents[idx[k]];
          in[k].tangent = float4((xf.model * float4(t.xyz(), 0.0f)).xyz(), t.w * ctx.winding_sign);
        }
        if (ctx.uv1) in[k].uv1 = mesh_vertices.uv1[idx[k]];
      }
      ClipVertex polygon[kMaxClippedVertices];
      const int n = clipTriangle(in, cut, guard, polygon);
      size_t pieces = 0;
      for (int k = 1; k + 1 < n; ++k) {
        const ClipVertex* fan[3] = {&polygon[0], &polygon[k], &polygon[k + 1]};
        ScreenVertex sv[3];
        for (int i = 0; i < 3; ++i) sv[i] = projectToScreen(fan[i]->position, width, height);
        const uint32_t record = nextRecord();
        RasterTriangle& raster = chunk.raster[record];
        if (!setupRaster(ctx, sv, raster, chunk.wide[record], orientation)) continue;
        ++chunk.size;
        VertexAttributes a[3];
        for (int i = 0; i < 3; ++i)
          a[i] = {fan[i]->normal, fan[i]->uv,      fan[i]->color, false,
                  fan[i]->world,  fan[i]->tangent, fan[i]->uv1};
        setupShade(ctx, sv, a, orientation, raster, face_normal(idx), id, material(local),
                   chunk.shade[record], chunk.extras[record]);
        bin(raster, record, chunk.shade[record]);
        ++pieces;
      }
      if (pieces == 0) {
        ++chunk.culled;
        ++chunk.cull_reasons.clipped_away;
      } else {
        chunk.clip_splits += pieces - 1;
      }
    };

    // One triangle through the same checks as the cull kernel. Inlined as the other lambdas:
    // left to itself GCC stopped inlining it once drawClipped grew, and the per-triangle loop
    // around drawWhole lost 12 instructions a triangle (bunny, callgrind).
    auto drawOne = [&](size_t t) __attribute__((always_inline)) {
      const size_t local = t - xf.triangle_base;
      const uint32_t idx[3] = {mesh.indices[local * 3], mesh.indices[local * 3 + 1],
                               mesh.indices[local * 3 + 2]};
      if (idx[0] >= vertex_count || idx[1] >= vertex_count || idx[2] >= vertex_count) {
        ++chunk.culled;
        ++chunk.cull_reasons.invalid;
        return;
      }
      const uint32_t c0 = outcodes[idx[0]], c1 = outcodes[idx[1]], c2 = outcodes[idx[2]];
      // Non-finite vertices drop their triangle; so does one wholly outside a frustum plane.
      const ScreenVertex& v0 = mesh_vertices.screen[idx[0]];
      const ScreenVertex& v1 = mesh_vertices.screen[idx[1]];
      const ScreenVertex& v2 = mesh_vertices.screen[idx[2]];
      if (((c0 | c1 | c2) & kNonFinite) || (c0 & c1 & c2 & kRejectPlanes)) {
        ++chunk.culled;
        countCullReason(ctx, c0, c1, c2, v0, v1, v2, chunk.cull_reasons);
        return;
      }
      if (const uint32_t cut = (c0 | c1 | c2) & kCutPlanes) {
        drawClipped(t, idx, cut);
        return;
      }
      const int64_t area = signedArea(v0, v1, v2);
      const PixelBox box =
          cullsArea(ctx, area) ? PixelBox{0, 0, -1, -1} : pixelBox(ctx, v0, v1, v2);
      if (box.empty()) {
        ++chunk.culled;
        countCullReason(ctx, c0, c1, c2, v0, v1, v2, chunk.cull_reasons);
        return;
      }
      drawWhole(t, idx, area, box);
    };

    // Eight triangles at a time through the cull kernel; the rest (and groups with an index
    // outside the mesh) one at a time.
    constexpr size_t kGroup = CullGroup::kLanes;
    const size_t stop = std::min(end, object_end);
    // Only the triangle ranges that frustum culling kept (cull.h): the rest would be dropped.
    TriangleRuns runs(cull, object_index);
    while (t < stop) {
      const size_t run_end = runs.next(t, stop);
      while (t < run_end) {
        const size_t local = t - xf.triangle_base;
        CullGroup group;
        if (run_end - t < kGroup ||
            !cull_group(&mesh.indices[local * 3], vertex_count, mesh_vertices.screen, outcodes,
                        grid.width, grid.height, object.cull, sample_reach, group)) {
          drawOne(t++);
          continue;
        }
        for (size_t l = 0; l < kGroup; ++l) {
          if (group.kind[l] == CullGroup::kCulled) {
            ++chunk.culled;
            if (chunk.count_reasons) {
              const uint32_t* idx = &mesh.indices[(local + l) * 3];
              countCullReason(ctx, outcodes[idx[0]], outcodes[idx[1]], outcodes[idx[2]],
                              mesh_vertices.screen[idx[0]], mesh_vertices.screen[idx[1]],
                              mesh_vertices.screen[idx[2]], chunk.cull_reasons);
            }
            continue;
          }
          const uint32_t* idx = &mesh.indices[(local + l) * 3];
          if (group.kind[l] == CullGroup::kClip) {
            drawClipped(t + l, idx, static_cast<uint32_t>(group.cut[l]));
            continue;
          }
          drawWhole(t + l, idx, static_cast<int64_t>(group.area[l]),
                    PixelBox{group.min_x[l], group.min_y[l], group.max_x[l], group.max_y[l]});
        }
        t += kGroup;
      }
    }
  }
  flush();
  // The batch kernel's streaming stores are weakly ordered: they reach memory before the tile
  // stage (on any thread) reads the records.
#if defined(__SSE2__)
  _mm_sfence();
#endif
}

}  // namespace tessera
