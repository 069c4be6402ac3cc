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

namespace {

// What every triangle of one object reads in the setup stage.
struct ObjectSetup {
  const Object& object;
  const ObjectTransforms& xf;
  const Mesh& mesh;
  size_t vertex_count;
  bool has_uv, has_color, has_materials;
  SetupContext ctx;
  // Flat shading lights the face; so do vertices of a mesh without normals. A mirrored object's
  // triangles compare it with their vertex normals (setup.cpp: the normals' facing).
  bool needs_face_normal;
  MeshVertices vertices;
  const uint16_t* outcodes;
  PlainGouraud plain_gouraud;
  bool flat_in_lanes;  // flatLitInLanes
  // alphaMode BLEND: such triangles wait for the transparent pass (blend.h), out of the bins.
  bool any_blended;
  // Its triangles' extras hold normals (writesNormals): staged, and written out with their batch.
  bool stages_extras = false;

  // Read only for the triangles that survive the cull.
  uint16_t material(size_t local) const {
    return has_materials ? mesh.triangle_materials[local] : uint16_t{0};
  }
  float3 faceNormal(const uint32_t idx[3]) const {
    if (!needs_face_normal) return float3{};
    const float3 p0 = mesh.positions[idx[0]], p1 = mesh.positions[idx[1]],
                 p2 = mesh.positions[idx[2]];
    return xf.normal_matrix * cross(p1 - p0, p2 - p0) * xf.winding_sign;
  }
};

// One chunk's setup (CpuRenderer::State::setupChunk), object by object.
class ChunkSetup {
 public:
  // `objects`, `cull`, `lights` and `kernels`: the renderer's, this frame's.
  ChunkSetup(const std::vector<ObjectTransforms>& objects, const FrustumCull& cull,
             const LightRig& lights, const Kernels& kernels, const Scene& scene,
             const VertexBuffer& vertices, const TileGrid& grid, const GuardBand& guard,
             bool want_normals, int32_t sample_reach, TriangleChunk& chunk)
      : objects_(objects),
        cull_(cull),
        lights_(lights),
        scene_(scene),
        vertices_(vertices),
        grid_(grid),
        guard_(guard),
        want_normals_(want_normals),
        sample_reach_(sample_reach),
        chunk_(chunk),
        setup_batch_(kernels.setup_batch),
        cull_group_(kernels.cull_group) {}

  // The triangles [t, stop) of object `object_index` (whose triangles the chunk holds some of).
  void drawObject(size_t object_index, size_t t, size_t stop);

  // The last batch; then a fence: the batch kernel's streaming stores are weakly ordered, and
  // they reach memory before the tile stage (on any thread) reads the records.
  void finish() {
    flush();
#if defined(__SSE2__)
    _mm_sfence();
#endif
  }

 private:
  ObjectSetup objectSetup(size_t object_index);
  __attribute__((always_inline)) inline uint32_t nextRecord();
  void growRecords();
  void flush();
  void writeExtras();
  __attribute__((always_inline)) inline void bin(const ObjectSetup& o, const auto& box,
                                                 uint32_t record, const ShadeTriangle& shade);
  __attribute__((always_inline)) inline void drawWhole(const ObjectSetup& o, size_t t,
                                                       const uint32_t idx[3], int64_t area,
                                                       const PixelBox& box);
  void drawClipped(const ObjectSetup& o, size_t t, const uint32_t idx[3], uint32_t cut);
  __attribute__((always_inline)) inline void drawOne(const ObjectSetup& o, size_t t);
  void countCulled(const ObjectSetup& o, size_t local, size_t l);

  const std::vector<ObjectTransforms>& objects_;
  const FrustumCull& cull_;
  const LightRig& lights_;
  const Scene& scene_;
  const VertexBuffer& vertices_;
  const TileGrid& grid_;
  const GuardBand& guard_;
  const bool want_normals_;
  const int32_t sample_reach_;
  TriangleChunk& chunk_;
  size_t objects_seen_ = 0;  // objectSetup's calls: the first sets chunk_.textured_alike
  TriangleOrientation orientation_;
  // Unclipped triangles wait here for the rest of their setup (setup_kernel.h). The kernel
  // depends on nothing per object, so one flush per full batch and one at the end of the chunk.
  SetupBatch batch_;
  const SetupBatchFn setup_batch_;
  const CullGroupFn cull_group_;
};

ObjectSetup ChunkSetup::objectSetup(size_t object_index) {
  const Object& object = scene_.objects[object_index];
  const ObjectTransforms& xf = objects_[object_index];
  const Mesh& mesh = *object.mesh;
  const size_t vertex_count = mesh.vertexCount();
  const bool has_uv = mesh.uvs.size() == vertex_count;
  const bool has_color = mesh.colors.size() == vertex_count;
  const SetupContext ctx = objectSetupContext(lights_, object, xf.model, grid_.width, grid_.height,
                                              want_normals_, sample_reach_);
  const MeshVertices mesh_vertices{
      vertices_.screen.data() + xf.vertex_base,
      vertices_.normal.data() + xf.vertex_base,
      litPerVertex(object, lights_) ? vertices_.lit.data() + xf.vertex_base : nullptr,
      has_uv ? mesh.uvs.data() : nullptr,
      has_color ? mesh.colors.data() : nullptr,
      mesh.positions.data(),
      meshUv1(ctx, mesh)};
  const bool has_materials = mesh.triangle_materials.size() == mesh.triangleCount();
  ObjectSetup o{object,
                xf,
                mesh,
                vertex_count,
                has_uv,
                has_color,
                has_materials,
                ctx,
                object.shading == Shading::kFlat || mesh.normals.size() != vertex_count ||
                    xf.winding_sign < 0.0f,
                mesh_vertices,
                vertices_.outcode.data() + xf.vertex_base,
                plainGouraudFor(ctx, mesh_vertices, has_materials),
                flatLitInLanes(ctx),
                false};
  // A mirrored object's front faces may show their vertex normals' back (setup.cpp).
  if (xf.winding_sign < 0.0f) o.plain_gouraud.applies = false;
  o.stages_extras = writesNormals(ctx.shading, want_normals_);
  chunk_.reads_normals |= o.stages_extras;
  chunk_.reads_world |= writesWorld(lights_, ctx.shading);
  chunk_.textured_plain |=
      ctx.has_uv && ctx.shading != Shading::kPhong && ctx.shading != Shading::kPbr;
  // One look at the object's materials. alphaMode MASK: the raster tests such triangles' alpha
  // (rasterMasked), in the chunks that hold one.
  bool albedo = false;
  for (const Material& m : object.materials) {
    chunk_.any_masked |= m.alpha_mode == AlphaMode::kMask;
    o.any_blended |= isBlended(m);
    albedo |= m.albedo != nullptr;
  }
  // Its records' has_uv: the mesh's UVs and the triangle's material's albedo (setup.cpp).
  chunk_.lit_alike &= ctx.shading == Shading::kPhong && !(ctx.has_uv && albedo);
  // Its records' material: materials[0] without per-triangle materials (setup.h).
  const Material* alike = !has_materials && ctx.has_uv && ctx.shading != Shading::kPhong &&
                                  ctx.shading != Shading::kPbr && object.materials[0].albedo
                              ? &object.materials[0]
                              : nullptr;
  chunk_.textured_alike = objects_seen_ > 0 && chunk_.textured_alike != alike ? nullptr : alike;
  ++objects_seen_;
  return o;
}

// The record slot of the next visible triangle: setup writes in place, and the slot counts
// (chunk.size) only once the triangle survives.
uint32_t ChunkSetup::nextRecord() {
  const uint32_t local = static_cast<uint32_t>(chunk_.size);
  if (local == chunk_.raster.size()) [[unlikely]]
    growRecords();
  return local;
}

// One more slot in each of the chunk's record arrays (a frame with more triangles than any before).
void ChunkSetup::growRecords() {
  TESSERA_CHECK(chunk_.size < kMaxTrianglesPerChunk) << "chunk holds too many triangles";
  chunk_.raster.emplace_back();
  chunk_.wide.emplace_back();
  chunk_.shade.emplace_back();
  chunk_.extras.emplace_back();
}

void ChunkSetup::flush() {
  if (batch_.count == 0) return;
  batch_.padLanes();
  setup_batch_(batch_, grid_.width, grid_.height, sample_reach_, chunk_.raster.data(),
               chunk_.wide.data(), chunk_.shade.data());
  if (batch_.extras_lanes != 0) writeExtras();
  batch_.count = 0;
  batch_.flat_lanes = 0;
  batch_.extras_lanes = 0;
}

// The batch's staged extras (SetupBatch::nextExtras) into their records: eight consecutive records
// starting on a line (21 whole lines) with streaming stores, as the setup kernel writes the
// shading records; others copied. Ordinary stores over last frame's extras, which the other
// worker's shading pass read, waited on that core for every line.
void ChunkSetup::writeExtras() {
#if defined(__SSE2__)
  char* const out = reinterpret_cast<char*>(&chunk_.extras[batch_.input[0].record]);
  if (batch_.extras_lanes == 0xffu && batch_.consecutive() &&
      (reinterpret_cast<uintptr_t>(out) & 63) == 0) {
    const char* in = reinterpret_cast<const char*>(batch_.extras);
    for (size_t i = 0; i < sizeof batch_.extras; i += 16)
      _mm_stream_si128(reinterpret_cast<__m128i*>(out + i),
                       _mm_load_si128(reinterpret_cast<const __m128i*>(in + i)));
    return;
  }
#endif
  for (int l = 0; l < batch_.count; ++l)
    if (batch_.extras_lanes & (1u << l)) chunk_.extras[batch_.input[l].record] = batch_.extras[l];
}

void ChunkSetup::bin(const ObjectSetup& o, const auto& box, uint32_t record,
                     const ShadeTriangle& shade) {
  if (o.any_blended && isBlended(*shade.material))
    chunk_.blended.push_back(record);
  else
    chunk_.bins.add(grid_, box, record);
}

// A triangle that passed the cull whole: binned now, in submission order; the edges and planes
// come eight at a time (flush).
void ChunkSetup::drawWhole(const ObjectSetup& o, size_t t, const uint32_t idx[3], int64_t area,
                           const PixelBox& box) {
  const size_t local = t - o.xf.triangle_base;
  const uint32_t id = static_cast<uint32_t>(t);
  const uint32_t record = nextRecord();
  ++chunk_.size;
  orient(area, orientation_);
  ShadeTriangle& shade = batch_.nextShade();
  if (o.flat_in_lanes) {
    // Lit eight faces at a time by the batch kernel, which also forms their normals: a face took
    // about 60 cycles of scalar square root, division and lights (docs/perf-notes/frame-passes.md),
    // and its normal (faceNormal) a third of the flat bunny's scalar setup.
    setupFlatCorners(o.ctx, o.vertices, idx, orientation_, id, o.material(local), shade);
    const float3 corners[3] = {o.mesh.positions[idx[0]], o.mesh.positions[idx[1]],
                               o.mesh.positions[idx[2]]};
    batch_.markFlat(corners, o.xf, orientation_.back_facing ? -1.0f : 1.0f, lights_);
  } else if (o.stages_extras) {
    // Extras that hold normals wait for the flush with the batch (writeExtras). Such objects are
    // never PlainGouraud (it wants Gouraud without the normal AOV).
    setupShadeCorners(o.ctx, o.vertices, idx, orientation_, o.faceNormal(idx), id,
                      o.material(local), shade, batch_.nextExtras());
  } else if (!plainGouraudCorners(o.ctx, o.plain_gouraud, o.vertices, idx, orientation_, id,
                                  o.material(local), shade, chunk_.extras[record])) {
    setupShadeCorners(o.ctx, o.vertices, idx, orientation_, o.faceNormal(idx), id,
                      o.material(local), shade, chunk_.extras[record]);
  }
  bin(o, box, record, shade);
  batch_.push(o.vertices.screen[idx[0]], o.vertices.screen[idx[1]], o.vertices.screen[idx[2]], area,
              record);
  if (batch_.full()) flush();
}

// A triangle crossing the near or far plane or leaving the guard band: clip, then fan.
void ChunkSetup::drawClipped(const ObjectSetup& o, size_t t, const uint32_t idx[3], uint32_t cut) {
  const size_t local = t - o.xf.triangle_base;
  const uint32_t id = static_cast<uint32_t>(t);
  ++chunk_.clipped;
  ClipVertex in[3];
  const bool needs_world = needsWorld(lights_, o.object.shading);
  for (int k = 0; k < 3; ++k) {
    const size_t v = o.xf.vertex_base + idx[k];
    in[k] = {vertices_.clip(v), vertices_.normal[v], o.has_uv ? o.mesh.uvs[idx[k]] : float2{},
             o.has_color ? o.mesh.colors[idx[k]] : float4{1, 1, 1, 1},
             needs_world ? (o.xf.model * float4(o.mesh.positions[idx[k]], 1.0f)).xyz() : float3{}};
    if (o.ctx.tangents) {
      const float4 tangent = o.ctx.tangents[idx[k]];
      in[k].tangent =
          float4((o.xf.model * float4(tangent.xyz(), 0.0f)).xyz(), tangent.w * o.ctx.winding_sign);
    }
    if (o.ctx.uv1) in[k].uv1 = o.vertices.uv1[idx[k]];
  }
  ClipVertex polygon[kMaxClippedVertices];
  const int n = clipTriangle(in, cut, guard_, polygon);
  const float width = static_cast<float>(grid_.width), height = static_cast<float>(grid_.height);
  size_t pieces = 0;
  for (int k = 1; k + 1 < n; ++k) {
    const ClipVertex* fan[3] = {&polygon[0], &polygon[k], &polygon[k + 1]};
    ScreenVertex sv[3];
    for (int i = 0; i < 3; ++i) sv[i] = projectToScreen(fan[i]->position, width, height);
    const uint32_t record = nextRecord();
    RasterTriangle& raster = chunk_.raster[record];
    if (!setupRaster(o.ctx, sv, raster, chunk_.wide[record], orientation_)) continue;
    ++chunk_.size;
    VertexAttributes a[3];
    for (int i = 0; i < 3; ++i)
      a[i] = {fan[i]->normal, fan[i]->uv,      fan[i]->color, false,
              fan[i]->world,  fan[i]->tangent, fan[i]->uv1};
    setupShade(o.ctx, sv, a, orientation_, raster, o.faceNormal(idx), id, o.material(local),
               chunk_.shade[record], chunk_.extras[record]);
    bin(o, raster, record, chunk_.shade[record]);
    ++pieces;
  }
  if (pieces == 0) {
    ++chunk_.culled;
    ++chunk_.cull_reasons.clipped_away;
  } else {
    chunk_.clip_splits += pieces - 1;
  }
}

// One triangle through the same checks as the cull kernel. Inlined as drawWhole: left to itself
// GCC stopped inlining it once drawClipped grew, and the per-triangle loop around drawWhole lost
// 12 instructions a triangle (bunny, callgrind).
void ChunkSetup::drawOne(const ObjectSetup& o, size_t t) {
  const size_t local = t - o.xf.triangle_base;
  const uint32_t idx[3] = {o.mesh.indices[local * 3], o.mesh.indices[local * 3 + 1],
                           o.mesh.indices[local * 3 + 2]};
  if (idx[0] >= o.vertex_count || idx[1] >= o.vertex_count || idx[2] >= o.vertex_count) {
    ++chunk_.culled;
    ++chunk_.cull_reasons.invalid;
    return;
  }
  const uint32_t c0 = o.outcodes[idx[0]], c1 = o.outcodes[idx[1]], c2 = o.outcodes[idx[2]];
  // Non-finite vertices drop their triangle; so does one wholly outside a frustum plane.
  const ScreenVertex& v0 = o.vertices.screen[idx[0]];
  const ScreenVertex& v1 = o.vertices.screen[idx[1]];
  const ScreenVertex& v2 = o.vertices.screen[idx[2]];
  if (((c0 | c1 | c2) & kNonFinite) || (c0 & c1 & c2 & kRejectPlanes)) {
    ++chunk_.culled;
    countCullReason(o.ctx, c0, c1, c2, v0, v1, v2, chunk_.cull_reasons);
    return;
  }
  if (const uint32_t cut = (c0 | c1 | c2) & kCutPlanes) {
    drawClipped(o, t, idx, cut);
    return;
  }
  const int64_t area = signedArea(v0, v1, v2);
  const PixelBox box =
      cullsArea(o.ctx, area) ? PixelBox{0, 0, -1, -1} : pixelBox(o.ctx, v0, v1, v2);
  if (box.empty() || missesEveryCentre(o.ctx, box, v0, v1, v2, area)) {
    ++chunk_.culled;
    countCullReason(o.ctx, c0, c1, c2, v0, v1, v2, chunk_.cull_reasons);
    return;
  }
  drawWhole(o, t, idx, area, box);
}

// Why triangle `l` of the cull group at `local` was culled by the kernel, counted (for a chunk that
// counts the reasons).
void ChunkSetup::countCulled(const ObjectSetup& o, size_t local, size_t l) {
  const uint32_t* idx = &o.mesh.indices[(local + l) * 3];
  countCullReason(o.ctx, o.outcodes[idx[0]], o.outcodes[idx[1]], o.outcodes[idx[2]],
                  o.vertices.screen[idx[0]], o.vertices.screen[idx[1]], o.vertices.screen[idx[2]],
                  chunk_.cull_reasons);
}

void ChunkSetup::drawObject(size_t object_index, size_t t, size_t stop) {
  const ObjectSetup o = objectSetup(object_index);
  // Eight triangles at a time through the cull kernel; the rest (and groups with an index
  // outside the mesh) one at a time.
  constexpr size_t kGroup = CullGroup::kLanes;
  // Only the triangle ranges that frustum culling kept (cull.h): the rest would be dropped.
  TriangleRuns runs(cull_, object_index);
  while (t < stop) {
    const size_t run_end = runs.next(t, stop);
    while (t < run_end) {
      const size_t local = t - o.xf.triangle_base;
      CullGroup group;
      if (run_end - t < kGroup ||
          !cull_group_(&o.mesh.indices[local * 3], o.vertex_count, o.vertices.screen, o.outcodes,
                       grid_.width, grid_.height, o.object.cull, sample_reach_, group)) {
        drawOne(o, t++);
        continue;
      }
      // The lanes the kernel kept, by their bits: a branch per lane on its kind missed wherever
      // the faces turned from the camera and back.
      unsigned kept = group.kept;
      if (chunk_.count_reasons)
        for (size_t l = 0; l < kGroup; ++l)
          if (!(kept >> l & 1u)) countCulled(o, local, l);
      // The kept lanes counted as they are drawn (the library's baseline x86-64 has no popcnt
      // instruction: __builtin_popcount was a call into libgcc, 0.8% of the bunny's frame at
      // 640x480).
      size_t drawn = 0;
      for (; kept != 0; kept &= kept - 1, ++drawn) {
        const size_t l = static_cast<size_t>(__builtin_ctz(kept));
        const uint32_t* idx = &o.mesh.indices[(local + l) * 3];
        if (group.kind[l] == CullGroup::kClip) {
          drawClipped(o, t + l, idx, static_cast<uint32_t>(group.cut[l]));
          continue;
        }
        drawWhole(o, t + l, idx, static_cast<int64_t>(group.area[l]),
                  PixelBox{group.min_x[l], group.min_y[l], group.max_x[l], group.max_y[l]});
      }
      chunk_.culled += kGroup - drawn;
      t += kGroup;
    }
  }
}

}  // namespace

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
  chunk.reads_normals = false;
  chunk.reads_world = false;
  chunk.textured_plain = false;
  chunk.lit_alike = true;
  chunk.textured_alike = nullptr;
  chunk.blended.clear();

  ChunkSetup setup(objects, cull, lights, kernels, scene, vertices, grid, guard, want_normals,
                   sample_reach, chunk);
  const size_t begin = chunk.first_triangle, end = begin + chunk.triangle_count;
  for (size_t t = begin, object_index = objectHolding(objects, begin); t < end; ++object_index) {
    const Object& object = scene.objects[object_index];
    const size_t object_end =
        objects[object_index].triangle_base + (object.mesh ? object.mesh->triangleCount() : 0);
    if (!object.mesh || t >= object_end) continue;
    const size_t stop = std::min(end, object_end);
    if (cull.drawsTriangles(object_index)) setup.drawObject(object_index, t, stop);
    t = stop;
  }
  setup.finish();
}

}  // namespace tessera
