// Shadow maps (render/shadow_map.h): a box on a floor under a directional light casts its shadow
// where the geometry says, touching the box, with no acne on lit surfaces; spot lights cast
// too; the images are the same bits for any worker count and instruction set.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <memory>

#include <tessera/render/cpu_renderer.h>
#include <tessera/scene/primitives.h>
#include <tessera/scene/scene.h>

#include "render_test_scenes.h"

#include "allocation_counter.h"  // allocationsAfterWarmUp

namespace tessera {
namespace {

constexpr int kSize = 1024;
// The light travels +x and down: the box's top edge at x = 0.5, y = 1 lands on the floor at x = 1.
const float3 kLightDirection = normalize(float3{1, -2, 0});

Object phongObject(Mesh mesh, Shading shading = Shading::kPhong) {
  Object o;
  o.mesh = std::make_shared<Mesh>(std::move(mesh));
  o.materials[0].base_color = {0.8f, 0.8f, 0.8f, 1};
  o.shading = shading;
  o.cull = CullMode::kNone;
  return o;
}

// A 10 x 10 floor at y = 0 (two triangles, normals up).
Mesh floorMesh() {
  Mesh m;
  m.positions = {{-5, 0, -5}, {-5, 0, 5}, {5, 0, 5}, {5, 0, -5}};
  m.normals = {{0, 1, 0}, {0, 1, 0}, {0, 1, 0}, {0, 1, 0}};
  m.indices = {0, 1, 2, 0, 2, 3};
  return m;
}

// The unit box standing on the floor (x, z in [-0.5, 0.5], y in [0, 1]) and the floor.
Scene boxOnFloor(Shading shading = Shading::kPhong) {
  Scene scene;
  scene.objects.push_back(phongObject(floorMesh(), shading));
  Object box = phongObject(makeCube(), shading);
  box.transform.translation = {0, 0.5f, 0};
  scene.objects.push_back(box);
  scene.lights.push_back(Light::directional(kLightDirection, {1, 1, 1}, 0.6f));
  scene.ambient = float3(0.1f);
  scene.camera.position = {0.5f, 6, 0};
  scene.camera.target = {0.5f, 0, 0};
  scene.camera.up = {0, 0, -1};
  scene.camera.near_z = 0.5f;
  scene.camera.far_z = 30;
  return scene;
}

RenderOptions options(bool shadows, int size = kSize) {
  RenderOptions o;
  o.width = o.height = size;
  o.normals = true;
  o.shadows.enabled = shadows;
  return o;
}

Frame render(const Scene& scene, const RenderOptions& o, int workers = 2,
             SimdLevel level = SimdLevel::kAuto) {
  return test::renderAt(scene, o, level, workers);
}

// Window position of world point p through the scene's camera.
float2 toWindow(const Scene& scene, float3 p, int width, int height) {
  const float aspect = static_cast<float>(width) / static_cast<float>(height);
  const float4 clip = scene.camera.projection(aspect) * scene.camera.view() * float4{p, 1.0f};
  return {(clip.x / clip.w * 0.5f + 0.5f) * width, (0.5f - clip.y / clip.w * 0.5f) * height};
}

int green(const Frame& f, int x, int y) {
  return static_cast<int>((f.color[static_cast<size_t>(y) * f.width + x] >> 8) & 0xff);
}

int channelDifference(uint32_t a, uint32_t b) {
  int d = 0;
  for (int s = 0; s < 24; s += 8)
    d = std::max(d,
                 std::abs(static_cast<int>((a >> s) & 0xff) - static_cast<int>((b >> s) & 0xff)));
  return d;
}

// Whether the floor point (x, 0, z) sees the light past the box (a slab test along -direction).
bool floorPointLit(float x, float z) {
  const float3 o{x, 0, z}, d = -kLightDirection;
  float t0 = 0, t1 = 1e9f;
  const float lo[3] = {-0.5f, 0.0f, -0.5f}, hi[3] = {0.5f, 1.0f, 0.5f};
  const float oc[3] = {o.x, o.y, o.z}, dc[3] = {d.x, d.y, d.z};
  for (int a = 0; a < 3; ++a) {
    if (dc[a] == 0.0f) {
      if (oc[a] < lo[a] || oc[a] > hi[a]) return true;
      continue;
    }
    float ta = (lo[a] - oc[a]) / dc[a], tb = (hi[a] - oc[a]) / dc[a];
    if (ta > tb) std::swap(ta, tb);
    t0 = std::max(t0, ta), t1 = std::min(t1, tb);
  }
  return t0 > t1;
}

TEST(Shadows, BoxShadowEdgeLandsWhereTheGeometrySays) {
  const Scene scene = boxOnFloor();
  const Frame shadowed = render(scene, options(true));
  const Frame plain = render(scene, options(false));
  // Along the floor's z = 0 line, beyond the box's top face: shadow from x = 0.5 to x = 1.
  const float2 edge = toWindow(scene, {1.0f, 0, 0}, kSize, kSize);
  const float2 base = toWindow(scene, {0.6f, 0, 0}, kSize, kSize);
  const int y = static_cast<int>(edge.y);
  const int lit = green(plain, static_cast<int>(edge.x) + 40, y);
  const int dark = green(shadowed, static_cast<int>(base.x), y);
  ASSERT_LT(dark + 40, lit) << "no shadow beside the box";
  // The first pixel past the midpoint between shadow and light, scanning outwards.
  const int mid = (lit + dark) / 2;
  int found = -1;
  for (int x = static_cast<int>(base.x); x < kSize; ++x)
    if (green(shadowed, x, y) >= mid) {
      found = x;
      break;
    }
  ASSERT_GE(found, 0);
  EXPECT_NEAR(found + 0.5f, edge.x, 2.0f) << "the edge at x = 1 projects to " << edge.x;
  // The same along the shadow's sides (z = +-0.5, x from 0.5 to 1).
  for (float side : {-0.5f, 0.5f}) {
    const float2 s = toWindow(scene, {0.75f, 0, side}, kSize, kSize);
    const int x = static_cast<int>(s.x);
    const int inward = side < 0 ? 1 : -1;  // the image's y grows with z (up is -z)
    int row = static_cast<int>(s.y) + inward * 20;
    ASSERT_LT(green(shadowed, x, row), mid);
    while (green(shadowed, x, row) < mid) row -= inward;
    EXPECT_NEAR(row + 0.5f, s.y, 2.0f) << "side z = " << side;
  }
}

TEST(Shadows, ShadowTouchesTheBoxBase) {
  // Seen from the shadow's side, low: the box's base against the floor is in view.
  Scene scene = boxOnFloor();
  scene.camera.position = {4, 2.5f, 0.5f};
  scene.camera.target = {0.5f, 0.3f, 0};
  scene.camera.up = {0, 1, 0};
  const Frame shadowed = render(scene, options(true));
  const Frame plain = render(scene, options(false));
  for (float z : {-0.3f, 0.0f, 0.3f}) {
    // Floor points two and five pixels' worth (about 0.01 and 0.025 units) from the base.
    for (float gap : {0.01f, 0.025f}) {
      const float2 w = toWindow(scene, {0.5f + gap, 0, z}, kSize, kSize);
      const int x = static_cast<int>(w.x), y = static_cast<int>(w.y);
      const int lit = green(plain, x, y), dark = green(shadowed, x, y);
      EXPECT_LT(dark + 60, lit) << "z " << z << ", " << gap << " from the base: " << dark
                                << " against " << lit;
    }
  }
}

TEST(Shadows, NoAcneWhereNothingOccludes) {
  const Scene scene = boxOnFloor();
  const Frame shadowed = render(scene, options(true));
  const Frame plain = render(scene, options(false));
  const float aspect = 1.0f;
  const float4x4 inv = inverse(scene.camera.projection(aspect) * scene.camera.view());
  const uint32_t floor_triangles = 2;
  int compared = 0, differing = 0;
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x) {
      const size_t i = static_cast<size_t>(y) * kSize + x;
      const uint32_t id = plain.triangle_id[i];
      if (id == kNoTriangle) continue;
      if (id <= floor_triangles) {
        // The floor point under the pixel, lit with a margin of 0.03 units (6 pixels) around.
        const float nx = (x + 0.5f) / kSize * 2 - 1, ny = 1 - (y + 0.5f) / kSize * 2;
        const float4 a = inv * float4{nx, ny, -1, 1}, b = inv * float4{nx, ny, 1, 1};
        const float3 p = a.xyz() / a.w, q = b.xyz() / b.w;
        const float3 f = p + (q - p) * (p.y / (p.y - q.y));
        bool lit = true;
        for (float dx : {-0.03f, 0.0f, 0.03f})
          for (float dz : {-0.03f, 0.0f, 0.03f}) lit = lit && floorPointLit(f.x + dx, f.z + dz);
        if (!lit) continue;
      }
      ++compared;
      differing += channelDifference(plain.color[i], shadowed.color[i]) > 1;
    }
  EXPECT_GT(compared, kSize * kSize / 2);
  EXPECT_EQ(differing, 0) << "of " << compared;
}

TEST(Shadows, NoAcneOnTheLitSideOfASphere) {
  for (Shading shading : {Shading::kPhong, Shading::kPbr}) {
    Scene scene;
    scene.objects.push_back(phongObject(makeUvSphere(96, 48), shading));
    scene.lights.push_back(Light::directional(normalize(float3{-1, -1, -1}), {1, 1, 1}, 0.8f));
    scene.ambient = float3(0.1f);
    scene.camera.position = {0, 0, 4};
    const Frame shadowed = render(scene, options(true, 512));
    const Frame plain = render(scene, options(false, 512));
    int compared = 0, differing = 0;
    for (size_t i = 0; i < plain.color.size(); ++i) {
      const float3 n = plain.normal[i];
      // Away from the terminator, where the faceted sphere's own triangles meet its smooth
      // normals at a grazing angle.
      if (plain.triangle_id[i] == kNoTriangle || -dot(n, scene.lights[0].direction) < 0.2f)
        continue;
      ++compared;
      differing += channelDifference(plain.color[i], shadowed.color[i]) > 1;
    }
    EXPECT_GT(compared, 10000);
    EXPECT_EQ(differing, 0) << "of " << compared << ", shading " << int(shading);
  }
}

TEST(Shadows, SpotLightCastsAShadow) {
  Scene scene = boxOnFloor();
  const float3 position{-3, 4, 0};
  scene.lights = {
      Light::spot(position, normalize(float3{3.5f, -4, 0}), {1, 1, 1}, 20.0f, 0.5f, 0.8f)};
  const Frame shadowed = render(scene, options(true, 512));
  const Frame plain = render(scene, options(false, 512));
  // (0.8, 0, 0) sees the light through the box; (-1.5, 0, 1.5) past it.
  const float2 hidden = toWindow(scene, {0.8f, 0, 0}, 512, 512);
  const float2 open = toWindow(scene, {-1.5f, 0, 1.5f}, 512, 512);
  const int hx = static_cast<int>(hidden.x), hy = static_cast<int>(hidden.y);
  const int ox = static_cast<int>(open.x), oy = static_cast<int>(open.y);
  EXPECT_LT(green(shadowed, hx, hy) + 40, green(plain, hx, hy));
  EXPECT_GT(green(plain, ox, oy), 40);
  EXPECT_EQ(green(shadowed, ox, oy), green(plain, ox, oy));
}

TEST(Shadows, FlatAndGouraudSurfacesStayUnshadowed) {
  for (Shading shading : {Shading::kFlat, Shading::kGouraud}) {
    const Scene scene = boxOnFloor(shading);
    EXPECT_EQ(render(scene, options(true, 256)).color, render(scene, options(false, 256)).color);
  }
}

TEST(Shadows, ImageIsBitIdenticalForEverySimdLevelAndWorkerCount) {
  Scene scene = boxOnFloor();
  scene.objects[1].shading = Shading::kPbr;
  scene.lights.push_back(
      Light::spot({-3, 4, 0}, normalize(float3{3.5f, -4, 0}), {1, 0.8f, 0.6f}, 10.0f, 0.5f, 0.8f));
  scene.camera.position = {4, 2.5f, 3};
  scene.camera.up = {0, 1, 0};
  for (Projection projection : {Projection::kPerspective, Projection::kFisheye}) {
    RenderOptions o = options(true, 256);
    o.projection = projection;
    for (int msaa : {1, 4}) {
      o.msaa = msaa;
      const Frame scalar = render(scene, o, 1, SimdLevel::kScalar);
      for (SimdLevel level :
           {SimdLevel::kSse2, SimdLevel::kAvx2, SimdLevel::kAvx512, SimdLevel::kAuto})
        for (int workers : {1, 2})
          EXPECT_EQ(scalar.color, render(scene, o, workers, level).color)
              << int(level) << ", " << workers << " workers, msaa " << msaa << ", projection "
              << int(projection);
    }
  }
}

TEST(Shadows, NonlinearProjectionsShadowToo) {
  Scene scene = boxOnFloor();
  scene.camera.position = {4, 2.5f, 0.5f};
  scene.camera.target = {0.5f, 0.3f, 0};
  scene.camera.up = {0, 1, 0};
  scene.camera.fov_y_degrees = 120;
  RenderOptions on = options(true, 256), off = options(false, 256);
  on.projection = off.projection = Projection::kSpherical;
  const Frame shadowed = render(scene, on), plain = render(scene, off);
  long darker = 0;
  for (size_t i = 0; i < plain.color.size(); ++i)
    darker += channelDifference(plain.color[i], shadowed.color[i]) > 40;
  EXPECT_GT(darker, 100);
  // A floor point in the box's shadow and one in the light, at their pixels of the equirectangular
  // mapping (ARCHITECTURE.md, Projections: theta = u s, phi = v s, s half the view angle).
  auto pixelOf = [&](float3 world) {
    const float3 d = (scene.camera.view() * float4{world, 1.0f}).xyz();
    const float s = radians(scene.camera.fov_y_degrees) * 0.5f;
    const float u = std::atan2(d.x, -d.z) / s, v = std::asin(d.y / length(d)) / s;
    const int x = static_cast<int>((u + 1.0f) * 0.5f * 256);
    const int y = static_cast<int>((1.0f - v) * 0.5f * 256);
    return static_cast<size_t>(y) * 256 + static_cast<size_t>(x);
  };
  const size_t hidden = pixelOf({0.75f, 0, 0}), open = pixelOf({2.0f, 0, 1.2f});
  EXPECT_GT(channelDifference(plain.color[hidden], shadowed.color[hidden]), 40);
  EXPECT_EQ(plain.color[open], shadowed.color[open]);
  for (size_t i : {hidden, open}) EXPECT_LE(plain.triangle_id[i], 2u) << "not the floor: " << i;
  EXPECT_NE(plain.triangle_id[open], kNoTriangle);
}

TEST(Shadows, FramesAfterWarmUpAllocateNothing) {
  Scene scene = boxOnFloor();
  scene.lights.push_back(
      Light::spot({-3, 4, 0}, normalize(float3{3.5f, -4, 0}), {1, 1, 1}, 10.0f, 0.5f, 0.8f));
  CpuRenderer renderer(2);
  RenderOptions o = options(true, 128);
  o.shadows.map_size = 256;
  Frame frame;
  // The light turns and the camera moves frame to frame; one frame is spherical.
  const size_t allocations = allocationsAfterWarmUp([&] {
    for (int i = 0; i < 3; ++i) {
      scene.lights[0].direction = normalize(float3{1, -2, 0.2f * static_cast<float>(i)});
      scene.camera.position.x = 0.5f + 0.1f * static_cast<float>(i);
      o.projection = i == 2 ? Projection::kSpherical : Projection::kPerspective;
      renderer.render(scene, o, frame);
    }
  });
  EXPECT_EQ(allocations, 0u);
}

}  // namespace
}  // namespace tessera
