// Tests of the CPU pipeline through its public seam, on scenes small enough to reason about
// pixel by pixel.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <map>
#include <new>
#include <random>
#include <set>
#include <thread>

#include <tessera/render/cpu_renderer.h>
#include <tessera/scene/color.h>
#include <tessera/scene/primitives.h>

#include "render/chunk_layout.h"
#include "render/clip.h"
#include "render/kernels.h"
#include "render/page_pool.h"
#include "render/replication.h"
#include "render/worker_pool.h"

using namespace tessera;

#include "allocation_counter.h"  // g_count_allocations, g_allocations

namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();

// A scene whose camera maps object coordinates straight to clip space.
Scene clipSpaceScene() {
  Scene scene;
  scene.camera.view_override = float4x4::identity();
  scene.camera.projection_override = float4x4::identity();
  scene.ambient = float3(1.0f);
  return scene;
}

// Window coordinates (pixels, y down) and NDC depth to a clip-space position with w = 1.
float3 windowToNdc(float x, float y, float z, int width, int height) {
  return {2.0f * x / width - 1.0f, 1.0f - 2.0f * y / height, z};
}

Object unlitObject(Mesh mesh, CullMode cull = CullMode::kNone) {
  Object o;
  o.mesh = std::make_shared<Mesh>(std::move(mesh));
  o.materials[0].base_color = {1, 1, 1, 1};
  o.shading = Shading::kUnlit;
  o.cull = cull;
  return o;
}

Frame renderScene(const Scene& scene, int width, int height, int workers = 1,
                  PipelineStats* stats = nullptr, bool normals = false) {
  CpuRenderer renderer(workers);
  RenderOptions options;
  options.width = width;
  options.height = height;
  options.normals = normals;
  Frame frame;
  renderer.render(scene, options, frame);
  if (stats) *stats = renderer.lastStats();
  return frame;
}

// The scene rendered with the kernels of one instruction set.
Frame renderAt(const Scene& scene, const RenderOptions& options, SimdLevel level, int workers) {
  CpuRenderer renderer(workers, level);
  Frame frame;
  renderer.render(scene, options, frame);
  return frame;
}

// One triangle given in window coordinates.
Mesh windowTriangle(float3 a, float3 b, float3 c, int width, int height) {
  Mesh m;
  m.positions = {windowToNdc(a.x, a.y, a.z, width, height),
                 windowToNdc(b.x, b.y, b.z, width, height),
                 windowToNdc(c.x, c.y, c.z, width, height)};
  m.indices = {0, 1, 2};
  return m;
}

int coveredCount(const Frame& f) {
  int n = 0;
  for (uint32_t id : f.triangle_id) n += id != kNoTriangle;
  return n;
}

}  // namespace

TEST(Raster, SharedEdgeGridCoversEachPixelOnce) {
  constexpr int kW = 64, kH = 48;
  // Vertex columns and rows on pixel centres (x.5) and off them; the 7x7 cells have diagonals
  // that pass exactly through pixel centres.
  const float xs[] = {0, 7.5f, 14.5f, 20.5f, 31.5f, 40.5f, 47.5f, 55.25f, 64};
  const float ys[] = {0, 5.5f, 12.5f, 18.5f, 29.5f, 36.5f, 48};
  std::vector<float3> triangles;
  for (int r = 0; r + 1 < 7; ++r) {
    for (int c = 0; c + 1 < 9; ++c) {
      float3 p00{xs[c], ys[r], 0}, p10{xs[c + 1], ys[r], 0}, p01{xs[c], ys[r + 1], 0},
          p11{xs[c + 1], ys[r + 1], 0};
      // Alternate the diagonal, and the winding, from cell to cell.
      bool flip = (r + c) % 2 == 1;
      if (flip)
        triangles.insert(triangles.end(), {p00, p10, p11, p00, p11, p01});
      else
        triangles.insert(triangles.end(), {p00, p01, p10, p10, p01, p11});
      if (c % 3 == 0) std::swap(triangles[triangles.size() - 1], triangles[triangles.size() - 2]);
    }
  }
  std::vector<int> coverage(kW * kH, 0);
  for (size_t t = 0; t < triangles.size(); t += 3) {
    Scene scene = clipSpaceScene();
    scene.objects.push_back(
        unlitObject(windowTriangle(triangles[t], triangles[t + 1], triangles[t + 2], kW, kH)));
    Frame f = renderScene(scene, kW, kH);
    for (int i = 0; i < kW * kH; ++i) coverage[i] += f.triangle_id[i] != kNoTriangle;
  }
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) EXPECT_EQ(coverage[y * kW + x], 1) << "pixel " << x << "," << y;
}

TEST(Raster, TopLeftRuleOnEdgesThroughPixelCentres) {
  constexpr int kW = 10, kH = 10;
  // A square whose four edges pass exactly through pixel centres: the top and left edges own
  // their centres, the bottom and right ones do not.
  Scene scene = clipSpaceScene();
  Mesh quad;
  for (float3 p :
       {float3{2.5f, 2.5f, 0}, float3{6.5f, 2.5f, 0}, float3{6.5f, 6.5f, 0}, float3{2.5f, 6.5f, 0}})
    quad.positions.push_back(windowToNdc(p.x, p.y, p.z, kW, kH));
  quad.indices = {0, 2, 1, 0, 3, 2};
  scene.objects.push_back(unlitObject(quad));
  Frame f = renderScene(scene, kW, kH);
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      bool inside = x >= 2 && x <= 5 && y >= 2 && y <= 5;
      EXPECT_EQ(f.idAt(x, y) != kNoTriangle, inside) << x << "," << y;
    }
}

TEST(Raster, TopLeftRuleForASingleTriangle) {
  constexpr int kW = 8, kH = 8;
  // Right triangle: horizontal top edge on row 1's centres (top: owned), vertical left edge on
  // column 1's centres (left: owned), hypotenuse through centres (bottom-right: not owned).
  Scene scene = clipSpaceScene();
  scene.objects.push_back(
      unlitObject(windowTriangle({1.5f, 1.5f, 0}, {5.5f, 1.5f, 0}, {1.5f, 5.5f, 0}, kW, kH)));
  Frame f = renderScene(scene, kW, kH);
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      // Centre (x+0.5, y+0.5) strictly inside or on an owned edge: x >= 1, y >= 1, x + y < 6.
      bool expected = x >= 1 && y >= 1 && (x + y) < 6;
      EXPECT_EQ(f.idAt(x, y) != kNoTriangle, expected) << x << "," << y;
    }
}

TEST(Raster, SubpixelTriangleBetweenCentresCoversNothing) {
  Scene scene = clipSpaceScene();
  scene.objects.push_back(
      unlitObject(windowTriangle({3.6f, 3.6f, 0}, {3.9f, 3.6f, 0}, {3.6f, 3.9f, 0}, 8, 8)));
  PipelineStats stats;
  Frame f = renderScene(scene, 8, 8, 1, &stats);
  EXPECT_EQ(coveredCount(f), 0);
  EXPECT_EQ(stats.triangles_setup, 0u);
  EXPECT_EQ(stats.triangles_culled, 1u);
}

TEST(Raster, TriangleFarOutsideTheGuardBandIsClippedAndFillsTheScreen) {
  constexpr int kW = 40, kH = 30;
  Scene scene = clipSpaceScene();
  Mesh huge;
  huge.positions = {{-1e6f, -1e6f, 0.0f}, {1e6f, -1e6f, 0.0f}, {0.0f, 1e6f, 0.0f}};
  huge.indices = {0, 1, 2};
  scene.objects.push_back(unlitObject(huge));
  PipelineStats stats;
  Frame f = renderScene(scene, kW, kH, 1, &stats);
  EXPECT_EQ(stats.triangles_clipped, 1u);
  EXPECT_EQ(coveredCount(f), kW * kH);
  for (float z : f.depth) EXPECT_NEAR(z, 0.5f, 1e-6f);
}

TEST(Raster, TriangleCrossingTheNearPlaneMatchesTheAnalyticFloor) {
  // A floor at y = -1 running from behind the camera to z = -40; the camera at the origin looks
  // down -Z with a 90 degree field of view.
  constexpr int kW = 64, kH = 48;
  Scene scene;
  scene.ambient = float3(1.0f);
  scene.camera.position = {0, 0, 0};
  scene.camera.target = {0, 0, -1};
  scene.camera.fov_y_degrees = 90.0f;
  scene.camera.near_z = 0.5f;
  scene.camera.far_z = 100.0f;
  Mesh floor;
  floor.positions = {{-30, -1, 10}, {30, -1, 10}, {30, -1, -40}, {-30, -1, -40}};
  floor.indices = {0, 1, 2, 0, 2, 3};
  scene.objects.push_back(unlitObject(floor, CullMode::kBack));
  PipelineStats stats;
  Frame f = renderScene(scene, kW, kH, 1, &stats);
  EXPECT_EQ(stats.triangles_clipped, 2u);

  const float aspect = static_cast<float>(kW) / kH;
  const float4x4 projection = scene.camera.projection(aspect);
  int checked = 0;
  for (int y = 0; y < kH; ++y) {
    for (int x = 0; x < kW; ++x) {
      float ndc_x = 2.0f * (x + 0.5f) / kW - 1.0f, ndc_y = 1.0f - 2.0f * (y + 0.5f) / kH;
      float3 dir{ndc_x * aspect, ndc_y, -1.0f};  // tan(45 deg) = 1
      bool hit = false;
      float t = 0;
      if (dir.y < 0) {
        t = -1.0f / dir.y;  // view distance along -Z
        float3 p = dir * t;
        // Skip pixels within a pixel's worth of the floor's far edge or sides.
        float margin = 0.6f * t * 2.0f / kH;
        if (std::fabs(p.z + 40.0f) < margin * 3 || std::fabs(std::fabs(p.x) - 30.0f) < margin * 3)
          continue;
        hit = p.z > -40.0f && std::fabs(p.x) < 30.0f;
      }
      EXPECT_EQ(f.idAt(x, y) != kNoTriangle, hit) << x << "," << y;
      if (hit) {
        float4 clip = projection * float4{dir * t, 1.0f};
        // Vertices snap to 1/256 pixel and the plane is evaluated in float: near the horizon
        // that moves depth by a few 1e-5.
        EXPECT_NEAR(f.depthAt(x, y), clip.z / clip.w * 0.5f + 0.5f, 1e-4f) << x << "," << y;
        ++checked;
      }
    }
  }
  EXPECT_GT(checked, kW * kH / 3);
}

TEST(Raster, InterpenetratingTrianglesResolveByDepth) {
  constexpr int kW = 32, kH = 16;
  Scene scene = clipSpaceScene();
  Mesh m;
  // Quad A leans from z = -0.5 (left, near) to z = 0.5 (right, far); quad B is flat at z = 0.
  m.positions = {{-1, -1, -0.5f}, {1, -1, 0.5f}, {1, 1, 0.5f}, {-1, 1, -0.5f},
                 {-1, -1, 0.0f},  {1, -1, 0.0f}, {1, 1, 0.0f}, {-1, 1, 0.0f}};
  m.indices = {0, 1, 2, 0, 2, 3, 4, 5, 6, 4, 6, 7};
  scene.objects.push_back(unlitObject(m));
  Frame f = renderScene(scene, kW, kH);
  for (int y = 0; y < kH; ++y) {
    for (int x = 0; x < kW; ++x) {
      uint32_t id = f.idAt(x, y);
      if (x < kW / 2 - 1) {
        EXPECT_TRUE(id == 1 || id == 2) << x << "," << y << " id " << id;
      }
      if (x > kW / 2) {
        EXPECT_TRUE(id == 3 || id == 4) << x << "," << y << " id " << id;
      }
      // Depth is the nearer of the two planes.
      float z_a = 0.5f * ((x + 0.5f) / kW * 2.0f - 1.0f) * 0.5f + 0.5f;
      EXPECT_NEAR(f.depthAt(x, y), std::min(z_a, 0.5f), 1e-6f);
    }
  }
}

TEST(Raster, HiZRejectsOnlyWhatIsHidden) {
  // A screen-covering wall at z = 0 drawn first (it sets the blocks' depth bounds), then small
  // and large triangles behind it (all hidden) and in front of it (all visible), interleaved.
  constexpr int kW = 128, kH = 96;
  Scene scene = clipSpaceScene();
  Mesh m;
  auto quad = [&](float x0, float y0, float x1, float y1, float z) {
    const uint32_t base = static_cast<uint32_t>(m.positions.size());
    m.positions.insert(m.positions.end(), {{x0, y0, z}, {x1, y0, z}, {x1, y1, z}, {x0, y1, z}});
    m.indices.insert(m.indices.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
  };
  quad(-1, -1, 1, 1, 0.0f);  // ids 1, 2
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> pos(-0.95f, 0.8f);
  std::vector<std::pair<float, float>> in_front;
  for (int i = 0; i < 60; ++i) {
    const float x = pos(rng), y = pos(rng);
    const float size = i % 10 == 0 ? 0.6f : 0.08f;  // some large, most small
    const bool front = i % 3 == 0;
    quad(x, y, x + size, y + size, front ? -0.2f - 0.001f * i : 0.3f);
    if (front) in_front.emplace_back(x, y);
  }
  scene.objects.push_back(unlitObject(m, CullMode::kBack));
  Frame f = renderScene(scene, kW, kH);
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      const uint32_t id = f.idAt(x, y);
      ASSERT_NE(id, kNoTriangle);
      // Triangle index id - 1 belongs to quad (id - 1) / 2; quad 0 is the wall, quad q >= 1 is
      // random quad q - 1, in front when (q - 1) % 3 == 0.
      const int q = static_cast<int>(id - 1) / 2;
      EXPECT_TRUE(q == 0 || (q - 1) % 3 == 0) << "hidden quad " << q << " at " << x << "," << y;
    }
  // Every quad in front owns the pixel at its lower-left corner's inside.
  for (auto [qx, qy] : in_front) {
    const int px = static_cast<int>((qx + 1.0f) * 0.5f * kW) + 1;
    const int py = static_cast<int>((1.0f - (qy + 0.02f)) * 0.5f * kH) - 1;
    const int q = static_cast<int>(f.idAt(px, py) - 1) / 2;
    EXPECT_NE(q, 0) << "a quad in front is missing at " << px << "," << py;
  }
}

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
            if (cullsArea(ctx, area) || box.empty()) {
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

TEST(Vertex, EveryInstructionSetTransformsToTheSameBits) {
  // Every instruction set's vertex kernel against the scalar one, field by field and bit for bit:
  // vertices in front of and behind the camera, beyond the guard band, on the w = 0 plane (screen
  // positions outside int32), NaN and infinite; zero and NaN normals; with and without normals
  // and lighting; ranges that start and end anywhere, so that the AVX-512 variant's sixteen-vertex
  // steps, the eight-vertex steps and the staged tail all run.
  using namespace tessera::render;
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> coordinate(-3.0f, 3.0f);
  std::uniform_int_distribution<int> pick(0, 19);
  const float inf = std::numeric_limits<float>::infinity();
  const float nan = std::numeric_limits<float>::quiet_NaN();
  // Enough vertices that a difference of one ulp before the snap to subpixels shows.
  const size_t kVertices = 2000;
  Mesh mesh;
  for (size_t i = 0; i < kVertices; ++i) {
    float3 p{coordinate(rng), coordinate(rng), coordinate(rng)};
    float3 n{coordinate(rng), coordinate(rng), coordinate(rng)};
    switch (pick(rng)) {
      case 0:
        p.x = nan;
        break;
      case 1:
        p.y = inf;
        break;
      case 2:
        p.z = 4.0f;
        break;  // on the camera's plane: w = 0
      case 3:
        p.z = 4.0f - 1e-7f;
        break;  // just in front of it: huge screen positions
      case 4:
        p = p * 400.0f;
        break;  // beyond the guard band
      case 7:
        p = p * (4.0f + coordinate(rng) * coordinate(rng));
        break;  // near its edges
      case 5:
        n = float3{};
        break;  // zero normal: lit is NaN
      case 6:
        n.x = nan;
        break;
      default:
        break;
    }
    mesh.positions.push_back(p);
    mesh.normals.push_back(n);
  }
  mesh.indices = {0, 1, 2};
  Object object;
  object.transform.rotation = quat::fromAxisAngle(normalize(float3{1, 2, 3}), 0.7f);
  object.transform.scale = float3{1.5f, 0.8f, 1.1f};
  Camera camera;
  camera.position = {0, 0, 4};
  const int width = 320, height = 200;
  const float4x4 view_projection =
      camera.projection(static_cast<float>(width) / height) * camera.view();
  ObjectTransforms transforms = makeObjectTransforms(object, view_projection);
  transforms.vertex_base = 5;
  const ViewportTransform viewport{static_cast<float>(width), static_cast<float>(height),
                                   makeGuardBand(width, height)};
  const ShadeLight lights[] = {
      shadeLight(Light::directional(normalize(float3{-1, -2, -1}), float3{0.9f, 0.8f, 0.7f})),
      shadeLight(Light::directional(normalize(float3{1, 0.5f, -1}), float3{0.2f, 0.3f, 0.4f}))};
  const VertexLighting lighting{float3{0.05f, 0.06f, 0.07f}, lights};
  Mesh without_normals = mesh;
  without_normals.normals.clear();

  auto run = [&](Isa isa, const Mesh& m, bool lit, size_t first, size_t count) {
    VertexBuffer out;
    out.resize(transforms.vertex_base + kVertices);
    kernelsFor(isa).transform_vertices(m, transforms, viewport, lit ? &lighting : nullptr, first,
                                       count, out);
    return out;
  };
  auto same = [](const auto& a, const auto& b, size_t from, size_t to) {
    return std::memcmp(a.data() + from, b.data() + from, (to - from) * sizeof(a[0])) == 0;
  };
  const std::pair<size_t, size_t> ranges[] = {{0, kVertices}, {3, 1000},          {17, 16},
                                              {1, 33},        {kVertices - 9, 9}, {20, 7}};
  int compared = 0;
  for (const Mesh* m : {&mesh, &without_normals}) {
    for (bool lit : {false, true}) {
      for (auto [first, count] : ranges) {
        const VertexBuffer reference = run(Isa::kScalar, *m, lit, first, count);
        const size_t from = transforms.vertex_base + first, to = from + count;
        for (Isa isa : {Isa::kSse2, Isa::kAvx2, Isa::kAvx512}) {
          if (isa > detectIsa()) continue;
          const VertexBuffer other = run(isa, *m, lit, first, count);
          const std::string what = std::string(isaName(isa)) + " from " + std::to_string(first) +
                                   " count " + std::to_string(count) + (lit ? " lit" : "") +
                                   (m == &mesh ? "" : " without normals");
          EXPECT_TRUE(same(reference.clip_x, other.clip_x, from, to)) << what;
          EXPECT_TRUE(same(reference.clip_y, other.clip_y, from, to)) << what;
          EXPECT_TRUE(same(reference.clip_z, other.clip_z, from, to)) << what;
          EXPECT_TRUE(same(reference.clip_w, other.clip_w, from, to)) << what;
          EXPECT_TRUE(same(reference.outcode, other.outcode, from, to)) << what;
          EXPECT_TRUE(same(reference.screen, other.screen, from, to)) << what;
          EXPECT_TRUE(same(reference.normal, other.normal, from, to)) << what;
          if (lit) {
            EXPECT_TRUE(same(reference.lit, other.lit, from, to)) << what;
          }
          ++compared;
        }
      }
    }
  }
  EXPECT_GT(compared, 0) << "no vector instruction set on this CPU to compare";
  // The inputs reach the cases they are meant to.
  const VertexBuffer all = run(Isa::kScalar, mesh, true, 0, kVertices);
  std::set<uint16_t> codes(all.outcode.begin() + 5, all.outcode.end());
  EXPECT_TRUE(codes.count(static_cast<uint16_t>(kNonFinite)));
  EXPECT_TRUE(codes.count(0));
  EXPECT_GT(codes.size(), 3u);
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

TEST(Raster, SetupBatchKernelMatchesSetupRaster) {
  // Every instruction set's batch kernel against the one-triangle setupRaster, on visible
  // triangles from a pixel to hundreds of pixels across (small ones keep their edge values at the
  // box corner, large ones c and z_min in RasterWide): the raster records byte for byte, the
  // large triangles' RasterWide, and the shading planes.
  using namespace tessera::render;
  std::mt19937 rng(5);
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
  std::uniform_int_distribution<int32_t> centre(-100 * kSubpixelOne, 700 * kSubpixelOne);
  std::uniform_real_distribution<float> depth(0.0f, 1.0f), inv_w(0.1f, 2.0f);
  const int32_t extents[] = {kSubpixelOne, 6 * kSubpixelOne, 40 * kSubpixelOne, 500 * kSubpixelOne};
  struct Triangle {
    ScreenVertex v[3];
    int64_t area;
  };
  std::vector<Triangle> triangles;
  while (triangles.size() < 400) {
    const int32_t extent = extents[rng() % 4];
    std::uniform_int_distribution<int32_t> offset(-extent, extent);
    const int32_t cx = centre(rng), cy = centre(rng);
    Triangle t;
    for (ScreenVertex& v : t.v) v = {cx + offset(rng), cy + offset(rng), depth(rng), inv_w(rng)};
    t.area = signedArea(t.v[0], t.v[1], t.v[2]);
    if (t.area == 0 || pixelBox(ctx, t.v[0], t.v[1], t.v[2]).empty()) continue;
    triangles.push_back(t);
  }
  // With one sample, and with MSAA's reach (boxes grown by half a pixel, the small test by more).
  for (int32_t reach : {0, kSampleReach}) {
    ctx.sample_reach = reach;
    std::vector<RasterTriangle> expected(triangles.size());
    std::vector<RasterWide> expected_wide(triangles.size());
    std::vector<ShadeTriangle> expected_shade(triangles.size());
    int small = 0;
    for (size_t i = 0; i < triangles.size(); ++i) {
      const Triangle& t = triangles[i];
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
        const Kernels kernels = kernelsFor(isa);
        PoolVector<RasterTriangle> raster(triangles.size());  // aligned: the kernel streams into it
        std::vector<RasterWide> wide(triangles.size());
        PoolVector<ShadeTriangle> shade(triangles.size());
        for (size_t first = 0; first < triangles.size(); first += first == 0 ? lead : 8) {
          SetupBatch batch;
          for (size_t i = first; i < std::min(first + (first == 0 ? lead : 8), triangles.size());
               ++i) {
            // The caller's part of the shading record, which the kernel carries to shade[record].
            ShadeTriangle& staged = batch.nextShade();
            staged.triangle_id = static_cast<uint32_t>(1000 + i);
            staged.color[2] = float3{static_cast<float>(i), 0.5f, 0.25f};
            batch.push(triangles[i].v[0], triangles[i].v[1], triangles[i].v[2], triangles[i].area,
                       static_cast<uint32_t>(i));
          }
          batch.padLanes();
          kernels.setup_batch(batch, width, height, reach, raster.data(), wide.data(),
                              shade.data());
        }
        for (size_t i = 0; i < triangles.size(); ++i) {
          SCOPED_TRACE(testing::Message() << isaName(isa) << " reach " << reach << " lead " << lead
                                          << " triangle " << i);
          ASSERT_EQ(0, std::memcmp(&raster[i], &expected[i], sizeof(RasterTriangle)));
          if (!expected[i].small()) {
            for (int k = 0; k < 3; ++k) EXPECT_EQ(wide[i].c[k], expected_wide[i].c[k]);
            EXPECT_EQ(wide[i].z_min, expected_wide[i].z_min);
          }
          // The planes, x0 .. sdy, as setupShade forms them.
          EXPECT_EQ(0, std::memcmp(&shade[i].x0, &expected_shade[i].x0, 9 * sizeof(float)));
          EXPECT_EQ(shade[i].triangle_id, 1000 + i);
          EXPECT_EQ(shade[i].color[2].x, static_cast<float>(i));
          EXPECT_EQ(shade[i].color[2].z, 0.25f);
        }
      }
  }
}

TEST(Raster, IdsFollowSceneTriangleOrderAcrossObjects) {
  Scene scene = clipSpaceScene();
  Mesh left, right;
  left.positions = {{-1, -1, 0}, {-0.1f, -1, 0}, {-1, 1, 0}, {-0.1f, 1, 0}};
  left.indices = {0, 1, 2, 1, 3, 2};
  right.positions = {{0.1f, -1, 0}, {1, -1, 0}, {0.1f, 1, 0}};
  right.indices = {0, 1, 2};
  scene.objects.push_back(unlitObject(left));
  scene.objects.push_back(unlitObject(right));
  Frame f = renderScene(scene, 20, 10);
  EXPECT_EQ(f.idAt(1, 8), 1u);  // lower-left: first triangle of the first object
  EXPECT_EQ(f.idAt(7, 1), 2u);
  EXPECT_EQ(f.idAt(12, 8), 3u);  // the second object's triangle follows the first's two
}

TEST(Shading, PerspectiveCorrectUvOnARecedingCheckerboard) {
  constexpr int kW = 96, kH = 64;
  constexpr int kChecks = 16;
  auto texture = std::make_shared<Texture>();
  texture->width = texture->height = kChecks;
  for (int y = 0; y < kChecks; ++y)
    for (int x = 0; x < kChecks; ++x)
      texture->texels.push_back((x + y) % 2 ? 0xffffffffu : 0xff000000u);

  Scene scene;
  scene.camera.position = {0, 1, 0};
  scene.camera.target = {0, 0.2f, -4};
  scene.camera.fov_y_degrees = 60;
  scene.camera.near_z = 0.1f;
  scene.camera.far_z = 100;
  // Floor y = 0 from z = -0.5 to z = -30.5, x in [-15, 15]; u along x, v along -z.
  const float z_near = -0.5f, z_far = -30.5f, half_x = 15.0f;
  Mesh floor;
  floor.positions = {
      {-half_x, 0, z_near}, {half_x, 0, z_near}, {half_x, 0, z_far}, {-half_x, 0, z_far}};
  floor.uvs = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  floor.indices = {0, 1, 2, 0, 2, 3};
  Object o = unlitObject(floor, CullMode::kBack);
  o.materials[0].albedo = texture;
  o.materials[0].sampler = {TextureFilter::kNearest, TextureWrap::kClamp};
  scene.objects.push_back(o);
  Frame f = renderScene(scene, kW, kH);

  const float aspect = static_cast<float>(kW) / kH;
  const float4x4 inverse_vp = inverse(scene.camera.projection(aspect) * scene.camera.view());
  int checked = 0, wrong = 0;
  for (int y = 0; y < kH; ++y) {
    for (int x = 0; x < kW; ++x) {
      // Unproject the pixel centre to a world ray and intersect it with the floor.
      float ndc_x = 2.0f * (x + 0.5f) / kW - 1.0f, ndc_y = 1.0f - 2.0f * (y + 0.5f) / kH;
      float4 a = inverse_vp * float4{ndc_x, ndc_y, -1, 1},
             b = inverse_vp * float4{ndc_x, ndc_y, 1, 1};
      float3 p0 = a.xyz() * (1 / a.w), p1 = b.xyz() * (1 / b.w);
      if (!(p1.y < p0.y)) continue;
      float3 hit = p0 + (p1 - p0) * (p0.y / (p0.y - p1.y));
      float u = (hit.x + half_x) / (2 * half_x), v = (z_near - hit.z) / (z_near - z_far);
      if (u <= 0 || u >= 1 || v <= 0 || v >= 1) continue;
      float tu = u * kChecks, tv = (1 - v) * kChecks;
      // Skip centres within a sliver of a check boundary, where rounding may go either way.
      float du = std::fabs(tu - std::round(tu)), dv = std::fabs(tv - std::round(tv));
      float slack = 0.02f * (1 + 20 * (v));
      if (du < slack || dv < slack) continue;
      bool white = (static_cast<int>(tu) + static_cast<int>(tv)) % 2 == 1;
      uint32_t expected = white ? 0xffffffffu : 0xff000000u;
      ++checked;
      wrong += f.colorAt(x, y) != expected;
    }
  }
  EXPECT_GT(checked, kW * kH / 4);
  EXPECT_EQ(wrong, 0) << "of " << checked;
}

TEST(Shading, TrilinearFilteringAveragesAFineCheckerInTheDistance) {
  // A fine checker on a floor running to the horizon: far away, many texels fall in one pixel.
  // Without mip levels the samples alias to black and white; with them they blend to grey.
  constexpr int kW = 120, kH = 80;
  auto texture = std::make_shared<Texture>();
  texture->width = texture->height = 256;
  for (int y = 0; y < 256; ++y)
    for (int x = 0; x < 256; ++x)
      texture->texels.push_back((x + y) % 2 ? 0xffffffffu : 0xff000000u);
  auto render = [&](bool mipmapped) {
    auto t = std::make_shared<Texture>(*texture);
    if (mipmapped) generateMipmaps(*t);
    Scene scene;
    scene.camera.position = {0, 0.5f, 0};
    scene.camera.target = {0, 0.3f, -4};
    scene.camera.near_z = 0.1f;
    scene.camera.far_z = 200;
    Mesh floor;
    floor.positions = {{-50, 0, -1}, {50, 0, -1}, {50, 0, -150}, {-50, 0, -150}};
    floor.uvs = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    floor.indices = {0, 1, 2, 0, 2, 3};
    Object o = unlitObject(floor, CullMode::kBack);
    o.materials[0].albedo = t;
    o.materials[0].sampler = {TextureFilter::kTrilinear, TextureWrap::kRepeat};
    scene.objects.push_back(o);
    return renderScene(scene, kW, kH);
  };
  // Pixels in the distant band that are far from the checker's mean (linear 0.5 = sRGB 188).
  auto extremes = [&](const Frame& f) {
    int top = 0;  // the first row with floor in it: the far edge, near the horizon
    while (top < kH && f.idAt(kW / 2, top) == kNoTriangle) ++top;
    int count = 0, covered = 0;
    for (int y = top; y < top + 4 && y < kH; ++y)
      for (int x = 0; x < kW; ++x) {
        if (f.idAt(x, y) == kNoTriangle) continue;
        ++covered;
        const uint32_t r = f.colorAt(x, y) & 0xff;
        count += std::abs(static_cast<int>(r) - 188) > 30;
      }
    EXPECT_GT(covered, kW * 3);
    return count;
  };
  const int aliased = extremes(render(false));
  const int filtered = extremes(render(true));
  EXPECT_GT(aliased, kW);
  EXPECT_LT(filtered, kW / 10);
}

TEST(Shading, LambertWithAmbientInLinearLight) {
  Scene scene = clipSpaceScene();
  scene.ambient = float3(0.1f);
  // A light shining straight at a face that looks at the viewer (+Z in clip space = towards
  // the viewer with the identity camera), at 60 degrees: cos = 0.5.
  scene.lights.push_back({normalize(float3{0, -std::sqrt(3.0f), -1}), float3(0.8f)});
  Mesh quad;
  quad.positions = {{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}};
  quad.indices = {0, 1, 2, 0, 2, 3};
  Object o = unlitObject(quad, CullMode::kBack);
  o.shading = Shading::kFlat;
  o.materials[0].base_color = {0.5f, 0.25f, 1.0f, 1.0f};
  scene.objects.push_back(o);
  Frame f = renderScene(scene, 8, 8);
  const float e = 0.1f + 0.8f * 0.5f;
  const uint32_t expected = packSrgba8({0.5f * e, 0.25f * e, 1.0f * e, 1.0f});
  for (uint32_t c : f.color) EXPECT_EQ(c, expected);
}

TEST(Shading, FlatGouraudAndPhongDifferAsExpectedOnASphere) {
  auto render = [](Shading shading) {
    Scene scene;
    scene.camera.position = {0, 0, 3};
    scene.lights.push_back({normalize(float3{-1, -1, -1}), float3(1.0f)});
    Object o;
    o.mesh = std::make_shared<Mesh>(makeUvSphere(12, 6));
    o.shading = shading;
    scene.objects.push_back(o);
    return renderScene(scene, 64, 64);
  };
  Frame flat = render(Shading::kFlat), gouraud = render(Shading::kGouraud),
        phong = render(Shading::kPhong);
  // Same coverage, different colours.
  EXPECT_EQ(flat.triangle_id, gouraud.triangle_id);
  EXPECT_EQ(flat.triangle_id, phong.triangle_id);
  EXPECT_NE(flat.color, gouraud.color);
  EXPECT_NE(gouraud.color, phong.color);
  // Flat: one colour per triangle.
  std::map<uint32_t, uint32_t> colour_of;
  for (size_t i = 0; i < flat.color.size(); ++i) {
    if (flat.triangle_id[i] == kNoTriangle) continue;
    auto [it, inserted] = colour_of.emplace(flat.triangle_id[i], flat.color[i]);
    EXPECT_EQ(it->second, flat.color[i]);
  }
  EXPECT_GT(colour_of.size(), 20u);
}

TEST(Shading, NormalAovIsUnitAndFacesTheViewer) {
  Scene scene;
  scene.camera.position = {0, 0, 3};
  Object o;
  o.mesh = std::make_shared<Mesh>(makeUvSphere(24, 12));
  o.shading = Shading::kPhong;
  scene.objects.push_back(o);
  Frame f = renderScene(scene, 48, 48, 1, nullptr, true);
  int covered = 0;
  for (size_t i = 0; i < f.pixelCount(); ++i) {
    if (f.triangle_id[i] == kNoTriangle) {
      EXPECT_EQ(f.normal[i], float3{});
      continue;
    }
    ++covered;
    EXPECT_NEAR(length(f.normal[i]), 1.0f, 1e-4f);
    EXPECT_GT(f.normal[i].z, -0.05f);
  }
  EXPECT_GT(covered, 48 * 48 / 4);
  // The centre pixel looks straight at the camera.
  EXPECT_GT(f.normal[24 * 48 + 24].z, 0.99f);
}

TEST(Lines, AxesAreDepthTestedButDoNotWriteDepth) {
  constexpr int kW = 40, kH = 20;
  Scene scene = clipSpaceScene();
  // A wall at NDC z = 0 over the left half; a red line at z = 0.5 (behind it) across the image.
  Mesh wall;
  wall.positions = {{-1, -1, 0}, {0, -1, 0}, {0, 1, 0}, {-1, 1, 0}};
  wall.indices = {0, 1, 2, 0, 2, 3};
  Object o = unlitObject(wall);
  o.materials[0].base_color = {0, 0, 1, 1};
  scene.objects.push_back(o);
  scene.lines.add({-1, 0.05f, 0.5f}, {1, 0.05f, 0.5f}, {1, 0, 0});
  Frame f = renderScene(scene, kW, kH);
  const uint32_t red = 0xff0000ffu, blue = 0xffff0000u;
  int red_right = 0;
  for (int x = 0; x < kW; ++x) {
    for (int y = 0; y < kH; ++y) {
      if (x < kW / 2) {
        EXPECT_EQ(f.colorAt(x, y), blue) << x << "," << y;
      }
      if (x >= kW / 2 && f.colorAt(x, y) == red) {
        ++red_right;
        EXPECT_EQ(f.depthAt(x, y), kInf);
      }
    }
  }
  EXPECT_GE(red_right, kW / 2 - 1);
}

TEST(Lines, WorldAxesPointAlongPositiveAxes) {
  Scene scene = clipSpaceScene();
  scene.show_world_axes = true;
  scene.world_axes_length = 0.9f;
  Frame f = renderScene(scene, 21, 21);
  // X (red) runs right from the centre, Y (green) runs up.
  EXPECT_EQ(f.colorAt(17, 10), 0xff0000ffu);
  EXPECT_EQ(f.colorAt(10, 3), 0xff00ff00u);
  EXPECT_EQ(f.colorAt(3, 10), packSrgba8(scene.background));
}

TEST(Renderer, ImageIsBitIdenticalForAnyWorkerCount) {
  Scene scene;
  scene.camera.position = {0, 2, 6};
  scene.camera.near_z = 0.5f;
  scene.lights.push_back({normalize(float3{-1, -2, -1}), float3(0.9f)});
  scene.show_world_axes = true;
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> unit(-1, 1);
  auto sphere = std::make_shared<Mesh>(makeUvSphere(20, 10));
  auto cube = std::make_shared<Mesh>(makeCube());
  for (int i = 0; i < 60; ++i) {
    Object o;
    o.mesh = i % 3 ? sphere : cube;
    o.shading = static_cast<Shading>(i % 4);
    o.cull = static_cast<CullMode>(i % 3);
    o.transform.translation = {unit(rng) * 4, unit(rng) * 3, unit(rng) * 6};  // some cross near
    o.transform.rotation = fromEuler({unit(rng), unit(rng), unit(rng)});
    o.transform.scale = float3(0.3f + 0.5f * std::fabs(unit(rng)));
    o.materials[0].base_color = {std::fabs(unit(rng)), std::fabs(unit(rng)), 0.5f, 1};
    o.show_axes = i % 7 == 0;
    scene.objects.push_back(o);
  }
  PipelineStats stats;
  Frame one = renderScene(scene, 333, 217, 1, &stats, true);
  EXPECT_GT(stats.triangles_clipped, 0u);
  EXPECT_GT(stats.triangles_setup, 1000u);
  for (int workers : {2, 7}) {
    Frame many = renderScene(scene, 333, 217, workers, nullptr, true);
    EXPECT_EQ(one.color, many.color) << workers << " workers";
    EXPECT_EQ(one.triangle_id, many.triangle_id) << workers << " workers";
    EXPECT_EQ(0, std::memcmp(one.depth.data(), many.depth.data(), one.depth.size() * 4));
    EXPECT_EQ(0, std::memcmp(one.normal.data(), many.normal.data(), one.normal.size() * 12));
  }
}

TEST(Renderer, ImageIsBitIdenticalForEverySimdLevel) {
  // Small triangles (a dense sphere), large ones (a floor through the near plane, screen-sized
  // quads), thin slivers and sub-pixel ones: both raster paths of every kernel variant.
  Scene scene;
  scene.camera.position = {0, 1, 4};
  scene.camera.near_z = 0.3f;
  scene.lights.push_back({normalize(float3{-1, -2, -1}), float3(0.9f)});
  Object sphere;
  sphere.mesh = std::make_shared<Mesh>(makeUvSphere(96, 48));
  sphere.shading = Shading::kPhong;
  scene.objects.push_back(sphere);
  Mesh floor;
  floor.positions = {{-40, -1, 30}, {40, -1, 30}, {40, -1, -40}, {-40, -1, -40}};
  floor.indices = {0, 1, 2, 0, 2, 3};
  Object floor_object;
  floor_object.mesh = std::make_shared<Mesh>(floor);
  scene.objects.push_back(floor_object);
  Mesh slivers;
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> unit(-1.5f, 1.5f);
  for (int i = 0; i < 400; ++i) {
    float3 a{unit(rng), unit(rng), unit(rng)};
    float3 b = a + float3{unit(rng), unit(rng), unit(rng)} * (i % 2 ? 1.0f : 0.004f);
    float3 c = a + (b - a) * 0.5f + float3{0.002f, -0.001f, 0.003f};
    uint32_t base = static_cast<uint32_t>(slivers.positions.size());
    slivers.positions.insert(slivers.positions.end(), {a, b, c});
    slivers.indices.insert(slivers.indices.end(), {base, base + 1, base + 2});
  }
  generateSmoothNormals(slivers);
  Object sliver_object;
  sliver_object.mesh = std::make_shared<Mesh>(slivers);
  sliver_object.cull = CullMode::kNone;
  sliver_object.shading = Shading::kGouraud;
  scene.objects.push_back(sliver_object);

  RenderOptions options;
  options.width = 301;
  options.height = 203;
  auto render = [&](SimdLevel level) { return renderAt(scene, options, level, 2); };
  Frame scalar = render(SimdLevel::kScalar);
  EXPECT_GT(coveredCount(scalar), 301 * 203 / 3);
  for (SimdLevel level :
       {SimdLevel::kSse2, SimdLevel::kAvx2, SimdLevel::kAvx512, SimdLevel::kAuto}) {
    Frame other = render(level);
    EXPECT_EQ(scalar.triangle_id, other.triangle_id) << static_cast<int>(level);
    EXPECT_EQ(scalar.color, other.color) << static_cast<int>(level);
    EXPECT_EQ(0, std::memcmp(scalar.depth.data(), other.depth.data(), scalar.depth.size() * 4));
  }
}

TEST(Renderer, PlainShadingIsTheSameForEverySimdLevelAndWithTheNormalAov) {
  // No texture and no Phong: eight pixels owned by several triangles are shaded lane by lane from
  // their own records. Asking for normals takes the per-triangle path instead; both, at every
  // instruction set, must give the same bits. Small triangles of three shading modes, some with
  // vertex colours, interpenetrating so that many eight-pixel runs have several owners.
  Scene scene;
  scene.camera.position = {0, 0.5f, 3};
  scene.lights.push_back({normalize(float3{-1, -2, -1}), float3(0.9f)});
  const Shading modes[] = {Shading::kGouraud, Shading::kFlat, Shading::kUnlit};
  for (int i = 0; i < 3; ++i) {
    Object o;
    Mesh mesh = makeUvSphere(80 + 10 * i, 40);
    for (size_t v = 0; i == 0 && v < mesh.positions.size(); ++v)
      mesh.colors.push_back({0.5f + 0.5f * std::sin(static_cast<float>(v)), 0.7f, 0.3f, 1});
    o.mesh = std::make_shared<Mesh>(mesh);
    o.shading = modes[i];
    o.transform.translation = {0.45f * static_cast<float>(i - 1), 0.1f * static_cast<float>(i), 0};
    o.materials[0].base_color = {0.3f + 0.3f * static_cast<float>(i), 0.8f, 0.5f, 1};
    scene.objects.push_back(o);
  }
  RenderOptions options;
  options.width = 257;
  options.height = 163;
  auto render = [&](SimdLevel level, bool normals) {
    options.normals = normals;
    return renderAt(scene, options, level, 2);
  };
  const Frame reference = render(SimdLevel::kScalar, true);
  EXPECT_GT(coveredCount(reference), 257 * 163 / 4);
  for (SimdLevel level : {SimdLevel::kScalar, SimdLevel::kSse2, SimdLevel::kAvx2,
                          SimdLevel::kAvx512, SimdLevel::kAuto}) {
    for (bool normals : {false, true}) {
      const Frame other = render(level, normals);
      EXPECT_EQ(reference.color, other.color) << static_cast<int>(level) << " " << normals;
      EXPECT_EQ(reference.triangle_id, other.triangle_id) << static_cast<int>(level);
    }
  }
}

TEST(Renderer, EncodesEveryColourTheSameAtEverySimdLevel) {
  // The sRGB encode (eight or, with AVX-512, sixteen lanes at a time) against the scalar
  // variant: an unlit quad filling the view, red rising from below 0 up the image, green and
  // blue across it (blue past 1), slowly enough that together the channels take every 8-bit
  // code, the linear segment near black and the clamps included. 257 pixels wide: the last tile's
  // rows end inside a sixteen-pixel step.
  Scene scene;
  scene.camera.position = {0, 0, 1};
  scene.camera.fov_y_degrees = 90.0f;
  Mesh quad;
  quad.positions = {{-0.6f, -1.05f, 0}, {0.6f, -1.05f, 0}, {0.6f, 1.05f, 0}, {-0.6f, 1.05f, 0}};
  quad.colors = {{-0.012f, 0.03f, 1.35f, 1},
                 {-0.012f, 0.42f, 0.28f, 1},
                 {0.09f, 0.42f, 0.28f, 1},
                 {0.09f, 0.03f, 1.35f, 1}};
  quad.indices = {0, 1, 2, 0, 2, 3};
  scene.objects.push_back(unlitObject(quad));
  RenderOptions options;
  options.width = 257;
  options.height = 509;
  const Frame reference = renderAt(scene, options, SimdLevel::kScalar, 1);
  std::set<uint32_t> codes;
  for (uint32_t c : reference.color)
    for (int shift : {0, 8, 16}) codes.insert((c >> shift) & 0xff);
  EXPECT_EQ(codes.size(), 256u) << "the channels together take every code";
  for (SimdLevel level : {SimdLevel::kSse2, SimdLevel::kAvx2, SimdLevel::kAvx512, SimdLevel::kAuto})
    EXPECT_EQ(reference.color, renderAt(scene, options, level, 1).color) << static_cast<int>(level);
}

TEST(Renderer, AllocatesNothingPerFrameAfterWarmUp) {
  Scene scene;
  scene.camera.position = {0, 0.5f, 2.5f};
  scene.camera.near_z = 1.8f;  // some triangles cross the near plane
  scene.lights.push_back({normalize(float3{-1, -2, -1}), float3(0.9f)});
  scene.show_world_axes = true;
  Object sphere;
  sphere.mesh = std::make_shared<Mesh>(makeUvSphere(64, 32));
  sphere.shading = Shading::kPhong;
  sphere.show_axes = true;
  scene.objects.push_back(sphere);
  CpuRenderer renderer(3);
  RenderOptions options;
  options.width = 320;
  options.height = 200;
  options.normals = true;
  Frame frame;
  // Warm up on the same frames: buffers grow to the largest frame seen, then stay.
  for (int pass = 0; pass < 2; ++pass) {
    if (pass == 1) {
      g_allocations = 0;
      g_count_allocations = true;
    }
    for (int i = 0; i < 3; ++i) {
      scene.objects[0].transform.rotation = quat::fromAxisAngle({0, 1, 0}, 0.1f * i);
      // With one sample and with MSAA (its sample layers, made once per worker), with and
      // without jitter.
      options.msaa = i == 2 ? 8 : 1;
      options.jitter = jitterOffset(static_cast<uint32_t>(i));
      renderer.render(scene, options, frame);
    }
  }
  g_count_allocations = false;
  EXPECT_GT(renderer.lastStats().triangles_clipped, 0u);
  EXPECT_EQ(g_allocations.load(), 0u);
}

// An animation with two workers, frame after frame, against one worker: the same bytes in every
// frame, while the two-worker renderer alternates and probes its two ways to run the vertex
// stage (render/replication.h) and its workers take their blocks of chunks and tiles.
TEST(Renderer, AnAnimationIsTheSameForOneAndTwoWorkers) {
  Scene scene;
  scene.camera.position = {0, 0.4f, 3};
  scene.lights.push_back({normalize(float3{-1, -1, -1}), float3(0.9f)});
  Object o;
  o.mesh = std::make_shared<Mesh>(makeUvSphere(96, 48));  // 9,216 triangles: three chunks
  o.shading = Shading::kGouraud;
  scene.objects.push_back(o);
  CpuRenderer one(1), two(2);
  RenderOptions options;
  options.width = 160;
  options.height = 120;
  Frame a, b;
  for (int frame = 0; frame < 24; ++frame) {
    scene.objects[0].transform.rotation = quat::fromAxisAngle({0, 1, 0}, 0.1f * frame);
    one.render(scene, options, a);
    two.render(scene, options, b);
    ASSERT_EQ(a.color, b.color) << "frame " << frame;
  }
  EXPECT_GT(coveredCount(a), 160 * 120 / 8);
}

TEST(Renderer, ReusesItsBuffersAcrossFramesAndSizes) {
  Scene scene;
  Object o;
  o.mesh = std::make_shared<Mesh>(makeCube());
  scene.objects.push_back(o);
  CpuRenderer renderer(2);
  RenderOptions options;
  Frame frame;
  options.width = 50, options.height = 40;
  renderer.render(scene, options, frame);
  Frame first = frame;
  options.width = 130, options.height = 70;
  renderer.render(scene, options, frame);
  EXPECT_EQ(frame.color.size(), 130u * 70u);
  options.width = 50, options.height = 40;
  renderer.render(scene, options, frame);
  EXPECT_EQ(frame.color, first.color);
  EXPECT_EQ(frame.triangle_id, first.triangle_id);
  // The same size, the cube turned and moved into one corner: nothing of the last frame's bins
  // is left over (setup empties only the tiles it filled).
  options.width = 160, options.height = 120;
  renderer.render(scene, options, frame);
  scene.objects[0].transform.rotation = quat::fromAxisAngle({0, 1, 0}, 0.7f);
  scene.objects[0].transform.translation = {1.2f, 0.9f, 0};
  renderer.render(scene, options, frame);
  CpuRenderer fresh(2);
  Frame expected;
  fresh.render(scene, options, expected);
  EXPECT_EQ(frame.color, expected.color);
  // While it learns, the renderer alternates between its two ways to run the vertex stage (once,
  // or once per worker: render/replication.h): the next two frames take one each.
  for (int i = 0; i < 2; ++i) {
    renderer.render(scene, options, frame);
    EXPECT_EQ(frame.color, expected.color) << i;
  }
}

TEST(Renderer, CameraInsideAClosedModelSeesItsInsideFaces) {
  Scene scene;
  scene.camera.position = {0.1f, 0.05f, 0.2f};
  scene.camera.target = {0, 0, -1};
  scene.camera.near_z = 0.01f;
  Object o;
  o.mesh = std::make_shared<Mesh>(makeCube());
  o.cull = CullMode::kNone;
  o.transform.scale = float3(2.0f);
  scene.objects.push_back(o);
  PipelineStats stats;
  Frame f = renderScene(scene, 64, 48, 2, &stats);
  EXPECT_EQ(coveredCount(f), 64 * 48);
  // With back faces culled the inside is invisible.
  scene.objects[0].cull = CullMode::kBack;
  EXPECT_EQ(coveredCount(renderScene(scene, 64, 48)), 0);
}

TEST(Renderer, EmptySceneIsAllBackground) {
  Scene scene;
  scene.background = {0.2f, 0.4f, 0.6f, 1.0f};
  Frame f = renderScene(scene, 7, 5);
  for (uint32_t c : f.color) EXPECT_EQ(c, packSrgba8(scene.background));
  for (float z : f.depth) EXPECT_EQ(z, kInf);
}

TEST(Renderer, AovsAreFilledOnlyWhenAskedAndDoNotChangeTheColour) {
  Scene scene;
  Object o;
  o.mesh = std::make_shared<Mesh>(makeUvSphere(16, 8));
  o.shading = Shading::kPhong;
  scene.objects.push_back(o);
  CpuRenderer renderer(2);
  RenderOptions options;
  options.width = 70;
  options.height = 50;
  Frame all, colour_only;
  options.normals = true;
  renderer.render(scene, options, all);
  options.depth = options.ids = options.normals = false;
  renderer.render(scene, options, colour_only);
  EXPECT_EQ(all.color, colour_only.color);
  EXPECT_EQ(all.depth.size(), 70u * 50u);
  EXPECT_EQ(all.normal.size(), 70u * 50u);
  EXPECT_TRUE(colour_only.depth.empty());
  EXPECT_TRUE(colour_only.triangle_id.empty());
  EXPECT_TRUE(colour_only.normal.empty());
  // Lines need depth: a scene with axes keeps a depth buffer.
  scene.show_world_axes = true;
  renderer.render(scene, options, colour_only);
  EXPECT_EQ(colour_only.depth.size(), 70u * 50u);
  EXPECT_TRUE(colour_only.triangle_id.empty());
}

// The vertex stage's two ways: alternated while both are timed, then the one with the lower
// median, the other every kProbeEvery-th frame; one slow frame does not flip it, a lasting change
// does, and a different scene starts over.
TEST(ReplicationChoice, KeepsTheFasterWayAndProbesTheOther) {
  using render::ReplicationChoice;
  ReplicationChoice choice;
  auto frame = [&](double replicated_ms, double shared_ms) {
    const bool way = choice.next(1000, 2000);
    choice.record(way, way ? replicated_ms : shared_ms);
    return way;
  };
  for (uint32_t f = 0; f < 2 * ReplicationChoice::kSamples; ++f)
    EXPECT_EQ(frame(2.0, 3.0), f % 2 == 0) << f;  // alternating while it learns
  EXPECT_TRUE(choice.preferred);
  // Replicated is faster: every frame replicated but one in kProbeEvery.
  int shared = 0;
  for (int f = 0; f < 64; ++f) shared += !frame(2.0, 3.0);
  EXPECT_EQ(shared, 64 / static_cast<int>(ReplicationChoice::kProbeEvery));
  // One very slow replicated frame changes nothing.
  choice.record(true, 50.0);
  EXPECT_TRUE(choice.preferred);
  // The host changes: sharing becomes the faster; after enough frames of each it is preferred.
  for (int f = 0; f < 200 && choice.preferred; ++f) frame(3.0, 2.0);
  EXPECT_FALSE(choice.preferred);
  int replicated = 0;
  for (int f = 0; f < 64; ++f) replicated += frame(3.0, 2.0);
  EXPECT_EQ(replicated, 64 / static_cast<int>(ReplicationChoice::kProbeEvery));
  // Another scene: learning again from the start.
  EXPECT_TRUE(choice.next(1001, 2000));
  EXPECT_EQ(choice.count[0] + choice.count[1], 0u);
  EXPECT_FALSE(choice.next(1001, 2000));
  // Replicating 1% faster is within the margin: the single transform is kept.
  ReplicationChoice close;
  for (int f = 0; f < 40; ++f) {
    const bool way = close.next(1000, 2000);
    close.record(way, way ? 1.98 : 2.0);
  }
  EXPECT_FALSE(close.preferred);
}

// Every index of every job runs exactly once, on a worker the pool has, whether the workers are
// spinning (jobs back to back) or asleep (a pause before the job) when it starts, and a job's
// results are all there when parallelFor returns. A worker may arrive late, during a later job.
TEST(WorkerPool, EveryIndexRunsOnceAndIsDoneOnReturn) {
  render::WorkerPool pool(3);
  ASSERT_EQ(pool.size(), 3);
  std::mt19937 rng(7);
  std::vector<std::atomic<int>> runs(600);
  for (int job = 0; job < 400; ++job) {
    const size_t count = 1 + rng() % runs.size();
    if (job % 25 == 0) std::this_thread::sleep_for(std::chrono::milliseconds(2));
    for (size_t i = 0; i < count; ++i) runs[i].store(0);
    std::atomic<int> bad_worker{0};
    pool.parallelFor(count, [&](size_t i, int worker) {
      if (worker < 0 || worker >= pool.size()) bad_worker.fetch_add(1);
      // The other workers finish their indices a little later than the caller would.
      if (worker != 0) std::this_thread::sleep_for(std::chrono::microseconds(20));
      runs[i].fetch_add(1);
    });
    ASSERT_EQ(bad_worker.load(), 0);
    for (size_t i = 0; i < count; ++i)
      ASSERT_EQ(runs[i].load(), 1) << "job " << job << " index " << i;
  }
}

TEST(PagePool, BlocksAreLineAlignedDisjointAndReusedBySize) {
  // Blocks of many sizes, filled with their own byte: none may overlap another or move off a
  // 64-byte boundary, and a freed block serves the next request of its size class.
  std::vector<std::pair<unsigned char*, size_t>> blocks;
  std::mt19937 random(7);
  for (int i = 0; i < 300; ++i) {
    const size_t bytes = size_t{1} << (random() % 19) | random() % 97;  // 1 B to ~256 KiB
    auto* block = static_cast<unsigned char*>(render::poolAllocate(bytes));
    ASSERT_EQ(reinterpret_cast<uintptr_t>(block) % 64, 0u) << bytes;
    std::memset(block, i & 0xff, bytes);
    blocks.push_back({block, bytes});
  }
  for (size_t i = 0; i < blocks.size(); ++i)
    for (size_t b = 0; b < blocks[i].second; ++b)
      ASSERT_EQ(blocks[i].first[b], static_cast<unsigned char>(i & 0xff)) << i << " " << b;
  // 100 bytes and 128 bytes share the 128-byte class; 129 does not.
  void* freed = render::poolAllocate(100);
  render::poolFree(freed, 100);
  void* again = render::poolAllocate(128);
  EXPECT_EQ(again, freed);
  void* other = render::poolAllocate(129);
  EXPECT_NE(other, freed);
  render::poolFree(again, 128);
  render::poolFree(other, 129);
  for (auto [block, bytes] : blocks) render::poolFree(block, bytes);
}

TEST(PagePool, LargeBlocksAndVectorsHoldTheirContents) {
  // Over 1 MiB a block is a mapping of its own, on a 2 MiB boundary.
  const size_t large = (size_t{3} << 20) + 5;
  auto* block = static_cast<unsigned char*>(render::poolAllocate(large));
  EXPECT_EQ(reinterpret_cast<uintptr_t>(block) % (size_t{2} << 20), 0u);
  block[0] = 1;
  block[large - 1] = 2;
  EXPECT_EQ(block[0] + block[large - 1], 3);
  render::poolFree(block, large);
  // A vector growing through every size class keeps what it holds.
  render::PoolVector<uint32_t> values;
  for (uint32_t i = 0; i < 1'000'000; ++i) values.push_back(i * 2654435761u);
  for (uint32_t i = 0; i < 1'000'000; ++i) ASSERT_EQ(values[i], i * 2654435761u) << i;
  EXPECT_EQ(reinterpret_cast<uintptr_t>(values.data()) % 64, 0u);
}
