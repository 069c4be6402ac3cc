// The CPU pipeline's setup stage through its public seam: back-face culling, the triangles it
// drops (non-finite, degenerate, out of range, missing every pixel centre), the cull and setup
// kernels against the per-triangle path, and how the triangles are laid out in chunks.
#include <gtest/gtest.h>

#include <cstring>
#include <limits>
#include <map>
#include <random>
#include <set>

#include <tessera/render/cpu_renderer.h>

#include "render/chunk_layout.h"
#include "render/kernels.h"
#include "render/page_pool.h"

#include "render_test_scenes.h"

using namespace tessera;
using namespace tessera::test;  // NOLINT(google-build-using-namespace)

TEST(Raster, BackfaceCullModes) {
  constexpr int kW = 16, kH = 8;
  Mesh m;
  // Left triangle counter-clockwise in NDC (front), right one clockwise (back).
  m.positions = {{-0.9f, -0.9f, 0}, {-0.1f, -0.9f, 0}, {-0.5f, 0.9f, 0},
                 {0.1f, -0.9f, 0},  {0.5f, 0.9f, 0},   {0.9f, -0.9f, 0}};
  m.indices = {0, 1, 2, 3, 4, 5};
  auto ids = [&](CullMode cull) {
    Scene scene = clipSpaceScene();
    scene.objects.push_back(unlitObject(m, cull));
    Frame f = renderScene(scene, kW, kH);
    std::set<uint32_t> seen(f.triangle_id.begin(), f.triangle_id.end());
    seen.erase(kNoTriangle);
    return seen;
  };
  EXPECT_EQ(ids(CullMode::kBack), (std::set<uint32_t>{1}));
  EXPECT_EQ(ids(CullMode::kFront), (std::set<uint32_t>{2}));
  EXPECT_EQ(ids(CullMode::kNone), (std::set<uint32_t>{1, 2}));
}

TEST(Raster, NonFiniteDegenerateAndOutOfRangeTrianglesAreDropped) {
  Scene scene = clipSpaceScene();
  Mesh m;
  const float nan = std::numeric_limits<float>::quiet_NaN();
  m.positions = {{-1, -1, 0}, {1, -1, 0}, {0, 1, 0}, {nan, 0, 0}, {0.5f, 0.5f, 0}, {kInf, 0, 0}};
  m.indices = {0, 1, 3,   // NaN vertex
               0, 1, 5,   // infinite vertex
               0, 2, 4,   // collinear? no: a real triangle, kept below
               0, 0, 1,   // degenerate
               0, 1, 99,  // index past the end
               0, 1, 2};  // valid
  scene.objects.push_back(unlitObject(m));
  PipelineStats stats;
  Frame f = renderScene(scene, 16, 16, 1, &stats);
  EXPECT_EQ(stats.triangles_in, 6u);
  EXPECT_EQ(stats.triangles_culled, 4u);
  std::set<uint32_t> seen(f.triangle_id.begin(), f.triangle_id.end());
  EXPECT_TRUE(seen.count(6));
  EXPECT_FALSE(seen.count(1) || seen.count(2) || seen.count(4) || seen.count(5));
}

TEST(Raster, DroppedTrianglesInsideGroupsOfEight) {
  // The pattern above three times over: setup culls eight triangles at a time, and a group
  // holding an index past the end is taken one triangle at a time.
  Scene scene = clipSpaceScene();
  Mesh m;
  const float nan = std::numeric_limits<float>::quiet_NaN();
  m.positions = {{-1, -1, 0}, {1, -1, 0}, {0, 1, 0}, {nan, 0, 0}, {0.5f, 0.5f, 0}, {kInf, 0, 0}};
  for (int copy = 0; copy < 3; ++copy)
    m.indices.insert(m.indices.end(), {0, 1, 3, 0, 1, 5, 0, 2, 4, 0, 0, 1, 0, 1, 99, 0, 1, 2});
  // Two more groups with nothing wrong in them: kept, culled by area, and off screen.
  m.positions.push_back({3, 3, 0});  // 6: outside the right and top planes
  m.positions.push_back({4, 3, 0});
  m.positions.push_back({3, 4, 0});
  for (int i = 0; i < 16; ++i) {
    if (i % 4 == 0) m.indices.insert(m.indices.end(), {0, 1, 2});  // drawn (last wins: equal z)
    if (i % 4 == 1) m.indices.insert(m.indices.end(), {0, 0, 2});  // zero area
    if (i % 4 == 2) m.indices.insert(m.indices.end(), {6, 7, 8});  // outside the frustum
    if (i % 4 == 3) m.indices.insert(m.indices.end(), {0, 2, 4});  // drawn
  }
  scene.objects.push_back(unlitObject(m));
  PipelineStats stats;
  Frame f = renderScene(scene, 16, 16, 1, &stats);
  EXPECT_EQ(stats.triangles_in, 34u);
  EXPECT_EQ(stats.triangles_culled, 12u + 8u);
  EXPECT_EQ(stats.triangles_setup, 6u + 8u);
  std::set<uint32_t> seen(f.triangle_id.begin(), f.triangle_id.end());
  // Ids are triangle index + 1; equal depths keep the first triangle drawn on a pixel.
  EXPECT_TRUE(seen.count(3)) << "the first kept real triangle";
  EXPECT_TRUE(seen.count(6)) << "the first valid triangle";
  for (uint32_t id : seen) {
    EXPECT_TRUE(id == kNoTriangle || id == 3 || id == 6) << id;
  }
}

// The cull kernel of every instruction set against setup's per-triangle functions, on random
// triangles: some cross a cut plane, some have a non-finite vertex or are wholly outside a plane,
// some are degenerate, back-facing or off the viewport.
TEST(Raster, CullKernelMatchesThePerTriangleChecks) {
  using namespace tessera::render;
  std::mt19937 rng(11);
  std::uniform_int_distribution<int32_t> coordinate(-300 * kSubpixelOne, 500 * kSubpixelOne);
  std::uniform_int_distribution<int> pick(0, 15);
  constexpr int kVertices = 64;
  std::vector<ScreenVertex> screen(kVertices);
  std::vector<uint16_t> outcodes(kVertices);
  for (int i = 0; i < kVertices; ++i) {
    const int kind = pick(rng);
    // A few vertices repeat another's position (degenerate triangles).
    screen[i] = i > 0 && kind == 0 ? screen[i - 1]
                                   : ScreenVertex{coordinate(rng), coordinate(rng), 0.5f, 1.0f};
    const uint32_t code = kind == 1   ? uint32_t{kClipNear}
                          : kind == 2 ? uint32_t{kNonFinite}
                          : kind == 3 ? uint32_t{kClipLeft}
                                      : 0u;
    outcodes[i] = static_cast<uint16_t>(code);
  }
  const int width = 201, height = 150;
  std::map<int, int> decided;  // how many lanes took each branch below
  for (Isa isa : {Isa::kScalar, Isa::kSse2, Isa::kAvx2, Isa::kAvx512}) {
    if (isa > detectIsa()) continue;
    const Kernels kernels = kernelsFor(isa);
    for (int32_t reach : {0, kSampleReach})
      for (CullMode cull : {CullMode::kBack, CullMode::kFront, CullMode::kNone}) {
        SetupContext ctx;
        ctx.width = width;
        ctx.height = height;
        ctx.cull = cull;
        ctx.sample_reach = reach;
        for (int group = 0; group < 200; ++group) {
          uint32_t indices[24];
          for (uint32_t& index : indices) index = static_cast<uint32_t>(rng() % kVertices);
          CullGroup out;
          ASSERT_TRUE(kernels.cull_group(indices, kVertices, screen.data(), outcodes.data(), width,
                                         height, cull, reach, out));
          for (int l = 0; l < 8; ++l) {
            const uint32_t* idx = &indices[3 * l];
            const uint32_t c0 = outcodes[idx[0]], c1 = outcodes[idx[1]], c2 = outcodes[idx[2]];
            SCOPED_TRACE(testing::Message()
                         << isaName(isa) << " cull " << static_cast<int>(cull) << " reach " << reach
                         << " group " << group << " lane " << l);
            EXPECT_EQ((out.kept >> l & 1u) != 0, out.kind[l] != CullGroup::kCulled);
            if (((c0 | c1 | c2) & kNonFinite) || (c0 & c1 & c2 & kRejectPlanes)) {
              EXPECT_EQ(out.kind[l], CullGroup::kCulled);
              ++decided[0];
              continue;
            }
            if (const uint32_t cut = (c0 | c1 | c2) & kCutPlanes) {
              EXPECT_EQ(out.kind[l], CullGroup::kClip);
              EXPECT_EQ(static_cast<uint32_t>(out.cut[l]), cut);
              ++decided[1];
              continue;
            }
            const ScreenVertex &v0 = screen[idx[0]], &v1 = screen[idx[1]], &v2 = screen[idx[2]];
            const int64_t area = signedArea(v0, v1, v2);
            const PixelBox box = pixelBox(ctx, v0, v1, v2);
            if (cullsArea(ctx, area) || box.empty() ||
                missesEveryCentre(ctx, box, v0, v1, v2, area)) {
              EXPECT_EQ(out.kind[l], CullGroup::kCulled);
              ++decided[cullsArea(ctx, area) ? 2 : 3];
              continue;
            }
            ++decided[4];
            ASSERT_EQ(out.kind[l], CullGroup::kVisible);
            EXPECT_EQ(static_cast<int64_t>(out.area[l]), area);
            EXPECT_EQ(out.min_x[l], box.min_x);
            EXPECT_EQ(out.min_y[l], box.min_y);
            EXPECT_EQ(out.max_x[l], box.max_x);
            EXPECT_EQ(out.max_y[l], box.max_y);
          }
        }
        // An index past the end: nothing decided, the caller goes one triangle at a time.
        uint32_t indices[24] = {};
        indices[17] = kVertices;
        CullGroup out;
        EXPECT_FALSE(kernels.cull_group(indices, kVertices, screen.data(), outcodes.data(), width,
                                        height, cull, reach, out));
      }
  }
  // Every branch was taken: dropped, clipped, culled by area, off the viewport, visible.
  for (int branch = 0; branch < 5; ++branch) EXPECT_GT(decided[branch], 20) << branch;
}

// Triangles about a pixel in size, their corners on a grid of 1/8 pixel within two pixels of a
// pixel centre, so that many edges run exactly through a centre (the top-left rule decides): the
// cull kernel of every instruction set, missesEveryCentre (one triangle at a time) and setupRaster
// (the raster's own edge values from the box's corner) drop the same ones.
TEST(Raster, FewCentresAreDroppedAlikeOnEveryPath) {
  using namespace tessera::render;
  std::mt19937 rng(23);
  std::uniform_int_distribution<int32_t> eighth(-15, 15), pixel(2, 60);
  const int width = 64, height = 64;
  SetupContext ctx;
  ctx.width = width;
  ctx.height = height;
  ctx.cull = CullMode::kNone;
  constexpr int kVertices = 24 * 256;
  std::vector<ScreenVertex> screen(kVertices);
  for (int t = 0; t < kVertices / 3; ++t) {
    const int32_t cx = pixel(rng) * kSubpixelOne + kSubpixelHalf;
    const int32_t cy = pixel(rng) * kSubpixelOne + kSubpixelHalf;
    // Half of them within one pixel (a box of one centre at most), half within two.
    const int32_t step = t % 2 ? 16 : 32;
    for (int k = 0; k < 3; ++k)
      screen[3 * t + k] = {cx + step * eighth(rng), cy + step * eighth(rng), 0.5f, 1.0f};
  }
  const std::vector<uint16_t> outcodes(kVertices, 0);
  std::map<int, int> missed, kept;  // by the box's centres
  int on_edge = 0;
  for (Isa isa : {Isa::kScalar, Isa::kSse2, Isa::kAvx2, Isa::kAvx512}) {
    if (isa > detectIsa()) continue;
    const Kernels kernels = kernelsFor(isa);
    for (int group = 0; group < kVertices / 24; ++group) {
      uint32_t indices[24];
      for (int i = 0; i < 24; ++i) indices[i] = static_cast<uint32_t>(24 * group + i);
      CullGroup out;
      ASSERT_TRUE(kernels.cull_group(indices, kVertices, screen.data(), outcodes.data(), width,
                                     height, CullMode::kNone, 0, out));
      for (int l = 0; l < 8; ++l) {
        const ScreenVertex* v = &screen[24 * group + 3 * l];
        const int64_t area = signedArea(v[0], v[1], v[2]);
        const PixelBox box = pixelBox(ctx, v[0], v[1], v[2]);
        if (area == 0 || box.empty()) continue;
        const bool misses = missesEveryCentre(ctx, box, v[0], v[1], v[2], area);
        RasterTriangle raster;
        RasterWide wide;
        TriangleOrientation o;
        SCOPED_TRACE(testing::Message() << isaName(isa) << " group " << group << " lane " << l);
        EXPECT_EQ(setupRaster(ctx, v[0], v[1], v[2], area, raster, wide, o), !misses);
        EXPECT_EQ(out.kind[l], misses ? CullGroup::kCulled : CullGroup::kVisible);
        if (isa != Isa::kScalar) continue;
        const int centres = (box.max_x - box.min_x + 1) * (box.max_y - box.min_y + 1);
        (misses ? missed : kept)[centres] += 1;
        // An edge through a centre of the box: a zero edge value before the top-left bias.
        for (int y = box.min_y; y <= box.max_y; ++y)
          for (int x = box.min_x; x <= box.max_x; ++x)
            for (int k = 0; k < 3; ++k) {
              const ScreenVertex &a = v[k], &b = v[(k + 1) % 3];
              const int64_t px = int64_t{x} * kSubpixelOne + kSubpixelHalf;
              const int64_t py = int64_t{y} * kSubpixelOne + kSubpixelHalf;
              on_edge += (int64_t{b.x} - a.x) * (py - a.y) == (int64_t{b.y} - a.y) * (px - a.x);
            }
      }
    }
  }
  // Boxes of one, two and four centres, some missed and some not; larger ones never dropped.
  for (int centres : {1, 2, 4}) {
    EXPECT_GT(missed[centres], 20) << centres;
    EXPECT_GT(kept[centres], 20) << centres;
  }
  EXPECT_GT(kept[3] + kept[6] + kept[9], 20);
  EXPECT_EQ(missed[3] + missed[6] + missed[9], 0);
  EXPECT_GT(on_edge, 50);
}

TEST(ChunkLayout, CoversEveryTriangleInOrderAndEndsEachBlockSmall) {
  using namespace tessera::render;
  for (size_t total : {size_t{0}, size_t{1}, size_t{100}, size_t{4096}, size_t{9216}, size_t{69666},
                       size_t{200000}, size_t{1000000}}) {
    const size_t chunk_size = std::max<size_t>(4096, (total + kMaxChunks - 1) / kMaxChunks);
    for (int workers : {1, 2, 3, 4}) {
      std::vector<TriangleChunk> chunks;
      const size_t count = layOutChunks(total, chunk_size, workers, chunks);
      const std::string what = std::to_string(total) + " triangles, " + std::to_string(workers);
      ASSERT_LE(count, kMaxChunks) << what;
      ASSERT_GE(chunks.size(), count) << what;
      size_t next = 0;
      for (size_t c = 0; c < count; ++c) {
        EXPECT_EQ(chunks[c].first_triangle, next) << what << ", chunk " << c;
        EXPECT_LE(chunks[c].triangle_count, chunk_size) << what << ", chunk " << c;
        next += chunks[c].triangle_count;
      }
      EXPECT_EQ(next, total) << what;
      // Where blocks end small (more chunks than equal ones), every worker's block but the last
      // (WorkerPool: count * w / n onwards) ends in chunks of a half, a quarter and an eighth.
      const bool tapered = count != (total + chunk_size - 1) / chunk_size;
      if (workers == 1 || total <= 4096 || total == 1000000) {
        EXPECT_FALSE(tapered) << what;  // one worker, no room for a head, or past kMaxChunks
      }
      if (total == 69666 || total == 200000) {
        EXPECT_EQ(tapered, workers > 1) << what;
      }
      if (tapered) {
        EXPECT_EQ(count % workers, 0u) << what;
        for (int w = 0; w + 1 < workers; ++w) {
          const size_t block_end = count * static_cast<size_t>(w + 1) / workers;
          EXPECT_EQ(chunks[block_end - 1].triangle_count, chunk_size / 8) << what << ", " << w;
          EXPECT_EQ(chunks[block_end - 2].triangle_count, chunk_size / 4) << what << ", " << w;
          EXPECT_EQ(chunks[block_end - 3].triangle_count, chunk_size / 2) << what << ", " << w;
        }
      }
    }
  }
  // The bunny with two workers: 11 chunks a block, the first ending in 2048, 1024 and 512.
  std::vector<TriangleChunk> chunks;
  ASSERT_EQ(layOutChunks(69666, 4096, 2, chunks), 22u);
  EXPECT_EQ(chunks[10].triangle_count, 512u);
  EXPECT_EQ(chunks[11].first_triangle, 34833u);
}

TEST(ChunkLayout, ChunksOfTheDrawnTrianglesTileTheScenesIndices) {
  using namespace tessera::render;
  // 10,000 objects of 1,000 triangles of which culling kept 3 whole and parts of 2: laid out over
  // the kept triangles, the chunks tile [0, total) in order and each holds the kept triangles
  // layOutChunks gave it (not one or two chunks holding them all).
  const size_t total = 10'000'000;
  const std::vector<IndexRange> drawn = {{4'000'000, 4'001'000},
                                         {4'001'000, 4'002'000},
                                         {4'002'500, 4'002'900},
                                         {7'000'000, 7'001'000},
                                         {9'999'000, 9'999'100}};
  size_t drawn_total = 0;
  for (const IndexRange& r : drawn) drawn_total += r.end - r.first;
  const auto kept_in = [&](size_t first, size_t end) {
    size_t n = 0;
    for (const IndexRange& r : drawn)
      n += std::min(end, r.end) - std::min(std::max(first, r.first), std::min(end, r.end));
    return n;
  };
  for (int workers : {1, 2, 3}) {
    std::vector<TriangleChunk> chunks;
    const size_t count = layOutChunks(drawn_total, 512, workers, chunks);
    std::vector<size_t> given(count);
    for (size_t c = 0; c < count; ++c) given[c] = chunks[c].triangle_count;
    toSceneIndices(drawn, total, chunks, count);
    size_t next = 0;
    for (size_t c = 0; c < count; ++c) {
      const std::string what = std::to_string(workers) + " workers, chunk " + std::to_string(c);
      EXPECT_EQ(chunks[c].first_triangle, next) << what;
      next += chunks[c].triangle_count;
      EXPECT_EQ(kept_in(chunks[c].first_triangle, next), given[c]) << what;
      EXPECT_LE(given[c], 512u) << what;
    }
    EXPECT_EQ(next, total) << workers;
    EXPECT_GE(count, 7u) << workers;
  }
  // Nothing kept: no chunk. Everything kept: the layout over the scene's indices, unchanged.
  std::vector<TriangleChunk> none;
  EXPECT_EQ(layOutChunks(0, 4096, 2, none), 0u);
  std::vector<TriangleChunk> all, plain;
  const size_t count = layOutChunks(69666, 4096, 2, all);
  ASSERT_EQ(layOutChunks(69666, 4096, 2, plain), count);
  toSceneIndices({{0, 69666}}, 69666, all, count);
  for (size_t c = 0; c < count; ++c) {
    EXPECT_EQ(all[c].first_triangle, plain[c].first_triangle) << c;
    EXPECT_EQ(all[c].triangle_count, plain[c].triangle_count) << c;
  }
}

namespace {

// A screen-space triangle and its signed area (setup's).
struct ScreenTriangle {
  render::ScreenVertex v[3];
  int64_t area;
};

// `count` random triangles that setup keeps in a viewport of ctx's size: from a pixel to hundreds
// of pixels across, some partly off the viewport.
std::vector<ScreenTriangle> visibleTriangles(const render::SetupContext& ctx, size_t count) {
  using namespace tessera::render;
  std::mt19937 rng(5);
  std::uniform_int_distribution<int32_t> centre(-100 * kSubpixelOne, 700 * kSubpixelOne);
  std::uniform_real_distribution<float> depth(0.0f, 1.0f), inv_w(0.1f, 2.0f);
  const int32_t extents[] = {kSubpixelOne, 6 * kSubpixelOne, 40 * kSubpixelOne, 500 * kSubpixelOne};
  std::vector<ScreenTriangle> triangles;
  while (triangles.size() < count) {
    const int32_t extent = extents[rng() % 4];
    std::uniform_int_distribution<int32_t> offset(-extent, extent);
    const int32_t cx = centre(rng), cy = centre(rng);
    ScreenTriangle t;
    for (ScreenVertex& v : t.v) v = {cx + offset(rng), cy + offset(rng), depth(rng), inv_w(rng)};
    t.area = signedArea(t.v[0], t.v[1], t.v[2]);
    const PixelBox box = pixelBox(ctx, t.v[0], t.v[1], t.v[2]);
    if (t.area == 0 || box.empty() || missesEveryCentre(ctx, box, t.v[0], t.v[1], t.v[2], t.area))
      continue;
    triangles.push_back(t);
  }
  return triangles;
}

// The records the setup batch kernel of `kernels` writes for `triangles`, in batches of eight
// after a first of `lead`; each triangle's staged shading record carries the id 1000 + i, the
// colour (i, 0.5, 0.25) and is solid for even i only (odd ones differ in corner 1's y, or in
// corner 2's z alone, the float markSolid8 reads apart from the others).
struct BatchRecords {
  render::PoolVector<render::RasterTriangle> raster;  // aligned: streamed into
  std::vector<render::RasterWide> wide;
  render::PoolVector<render::ShadeTriangle> shade;
};
BatchRecords setupInBatches(const render::Kernels& kernels,
                            const std::vector<ScreenTriangle>& triangles, size_t lead, int width,
                            int height, int32_t reach) {
  using namespace tessera::render;
  BatchRecords out{PoolVector<RasterTriangle>(triangles.size()),
                   std::vector<RasterWide>(triangles.size()),
                   PoolVector<ShadeTriangle>(triangles.size())};
  for (size_t first = 0; first < triangles.size(); first += first == 0 ? lead : 8) {
    SetupBatch batch;
    for (size_t i = first; i < std::min(first + (first == 0 ? lead : 8), triangles.size()); ++i) {
      // The caller's part of the shading record, which the kernel carries to shade[record].
      ShadeTriangle& staged = batch.nextShade();
      staged.triangle_id = static_cast<uint32_t>(1000 + i);
      staged.color[2] = float3{static_cast<float>(i), 0.5f, 0.25f};
      staged.color[0] = staged.color[1] = staged.color[2];
      if (i % 4 == 1) staged.color[1].y = 0.75f;
      if (i % 4 == 3) staged.color[0].z = staged.color[1].z = 0.3f;
      batch.push(triangles[i].v[0], triangles[i].v[1], triangles[i].v[2], triangles[i].area,
                 static_cast<uint32_t>(i));
    }
    batch.padLanes();
    kernels.setup_batch(batch, width, height, reach, out.raster.data(), out.wide.data(),
                        out.shade.data());
  }
  return out;
}

}  // namespace

TEST(Raster, SetupBatchKernelMatchesSetupRaster) {
  // Every instruction set's batch kernel against the one-triangle setupRaster, on visible
  // triangles from a pixel to hundreds of pixels across (small ones keep their edge values at the
  // box corner, large ones c and z_min in RasterWide): the raster records byte for byte, the
  // large triangles' RasterWide, and the shading planes.
  using namespace tessera::render;
  const int width = 640, height = 480;
  Scene scene;
  Object object;
  object.materials = {Material{}};
  SetupContext ctx;
  ctx.width = width;
  ctx.height = height;
  ctx.cull = CullMode::kNone;
  ctx.shading = Shading::kFlat;
  LightRig lights;
  lights.prepare(scene);
  ctx.lights = &lights;
  ctx.object = &object;
  const std::vector<ScreenTriangle> triangles = visibleTriangles(ctx, 400);
  // With one sample, and with MSAA's reach (boxes grown by half a pixel, the small test by more).
  for (int32_t reach : {0, kSampleReach}) {
    ctx.sample_reach = reach;
    std::vector<RasterTriangle> expected(triangles.size());
    std::vector<RasterWide> expected_wide(triangles.size());
    std::vector<ShadeTriangle> expected_shade(triangles.size());
    int small = 0;
    for (size_t i = 0; i < triangles.size(); ++i) {
      const ScreenTriangle& t = triangles[i];
      TriangleOrientation o;
      ASSERT_TRUE(
          setupRaster(ctx, t.v[0], t.v[1], t.v[2], t.area, expected[i], expected_wide[i], o));
      const VertexAttributes a{};
      const VertexAttributes attributes[3] = {a, a, a};
      ShadeExtras extras;
      setupShade(ctx, t.v, attributes, o, expected[i], float3{0, 0, 1}, 0, 0, expected_shade[i],
                 extras);
      small += expected[i].small();
    }
    EXPECT_GT(small, 100);
    EXPECT_GT(static_cast<int>(triangles.size()) - small, 50);

    // lead 8: full batches of records on whole lines (streamed as lines); lead 3: a short first
    // batch, after which the batches' records start inside a line (streamed record by record).
    for (Isa isa : {Isa::kScalar, Isa::kSse2, Isa::kAvx2, Isa::kAvx512})
      for (size_t lead : {size_t{8}, size_t{3}}) {
        if (isa > detectIsa()) continue;
        const BatchRecords r =
            setupInBatches(kernelsFor(isa), triangles, lead, width, height, reach);
        for (size_t i = 0; i < triangles.size(); ++i) {
          SCOPED_TRACE(testing::Message() << isaName(isa) << " reach " << reach << " lead " << lead
                                          << " triangle " << i);
          ASSERT_EQ(0, std::memcmp(&r.raster[i], &expected[i], sizeof(RasterTriangle)));
          if (!expected[i].small()) {
            for (int k = 0; k < 3; ++k) EXPECT_EQ(r.wide[i].c[k], expected_wide[i].c[k]);
            EXPECT_EQ(r.wide[i].z_min, expected_wide[i].z_min);
          }
          // The planes, x0 .. sdy, as setupShade forms them.
          EXPECT_EQ(0, std::memcmp(&r.shade[i].x0, &expected_shade[i].x0, 9 * sizeof(float)));
          EXPECT_EQ(r.shade[i].triangle_id, 1000 + i);
          EXPECT_EQ(r.shade[i].color[2].x, static_cast<float>(i));
          EXPECT_EQ(r.shade[i].color[2].z, 0.25f);
          EXPECT_EQ(r.shade[i].solid, i % 2 == 0);
        }
      }
  }
}
