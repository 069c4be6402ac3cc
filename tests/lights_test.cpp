// Lights (tessera/scene/scene.h: Light): KHR_lights_punctual's units and falloffs on the CPU
// renderer, the same bits on every instruction set and worker count, the glTF extension's parsing
// and the CLI's --light.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

#include <tessera/io/model_loader.h>
#include <tessera/render/cpu_renderer.h>
#include <tessera/scene/color.h>

#include "render/lights.h"
#include "run_process.h"
#include "temp_folder.h"

using namespace tessera;

#include "allocation_counter.h"  // allocationsAfterWarmUp

namespace {

constexpr int kSize = 129;     // pixels a side; odd, so a pixel centre sits on the axis
constexpr float kHalf = 4.0f;  // the plane spans [-kHalf, kHalf]^2 in world x, y

// A white plane at z = 0 facing +Z, seen straight down through an orthographic camera that maps
// world x, y in [-kHalf, kHalf] to the whole image; no ambient, black background.
Scene planeScene(Shading shading = Shading::kPhong, int cells = 1) {
  Mesh mesh;
  for (int y = 0; y <= cells; ++y)
    for (int x = 0; x <= cells; ++x) {
      mesh.positions.push_back({kHalf * (2.0f * x / cells - 1), kHalf * (2.0f * y / cells - 1), 0});
      mesh.normals.push_back({0, 0, 1});
    }
  for (int y = 0; y < cells; ++y)
    for (int x = 0; x < cells; ++x) {
      const uint32_t a = static_cast<uint32_t>(y * (cells + 1) + x), b = a + 1,
                     c = a + static_cast<uint32_t>(cells + 1), d = c + 1;
      mesh.indices.insert(mesh.indices.end(), {a, b, d, a, d, c});
    }
  Object plane;
  plane.mesh = std::make_shared<Mesh>(std::move(mesh));
  plane.materials[0].base_color = {1, 1, 1, 1};
  plane.shading = shading;
  plane.cull = CullMode::kNone;
  Scene scene;
  scene.objects.push_back(plane);
  scene.ambient = float3(0.0f);
  scene.background = {0, 0, 0, 1};
  scene.camera.view_override = float4x4::identity();
  scene.camera.projection_override = scaling({1 / kHalf, 1 / kHalf, 0.1f});
  return scene;
}

Frame renderPlane(const Scene& scene, int workers = 1, SimdLevel simd = SimdLevel::kAuto) {
  CpuRenderer renderer(workers, simd);
  RenderOptions options;
  options.width = options.height = kSize;
  Frame frame;
  renderer.render(scene, options, frame);
  return frame;
}

// The world x of pixel column px (and y of row py, flipped).
float worldX(int px) {
  return ((px + 0.5f) / kSize * 2 - 1) * kHalf;
}

// The red channel of pixel (x, y) in linear light.
float linearRed(const Frame& f, int x, int y) {
  return decodeSrgb8(static_cast<uint8_t>(f.color[static_cast<size_t>(y * f.width + x)] & 255u));
}

}  // namespace

TEST(Lights, PointIrradianceFallsWithInverseSquare) {
  // The pixel at the centre sees the point right under the light: irradiance I / d^2.
  const int c = kSize / 2;
  float value[2];
  const float distance[2] = {1.5f, 3.0f}, intensity = 1.8f;
  for (int i = 0; i < 2; ++i) {
    Scene scene = planeScene();
    scene.lights.push_back(Light::point({0, 0, distance[i]}, float3(1.0f), intensity));
    value[i] = linearRed(renderPlane(scene), c, c);
    EXPECT_NEAR(value[i], intensity / (distance[i] * distance[i]),
                0.02f * intensity / (distance[i] * distance[i]));
  }
  // Twice the distance, a quarter of the light (1/d would give a half).
  EXPECT_NEAR(value[0] / value[1], 4.0f, 0.12f);
}

TEST(Lights, SpotConeEdgesLandWhereTheAnglesSay) {
  const float height = 2.0f;
  const float inner = 20.0f * std::numbers::pi_v<float> / 180,
              outer = 35.0f * std::numbers::pi_v<float> / 180;
  Scene scene = planeScene();
  scene.lights.push_back(Light::spot({0, 0, height}, {0, 0, -1}, float3(1.0f), 4.0f, inner, outer));
  Scene point = planeScene();
  point.lights.push_back(Light::point({0, 0, height}, float3(1.0f), 4.0f));
  const Frame spot_frame = renderPlane(scene), point_frame = renderPlane(point);
  const int row = kSize / 2;
  int inside = 0, outside = 0, between = 0;
  for (int x = 0; x < kSize; ++x) {
    const float angle = std::atan(std::fabs(worldX(x)) / height);
    const float spot = linearRed(spot_frame, x, row), full = linearRed(point_frame, x, row);
    if (angle < inner - 0.01f) {
      EXPECT_EQ(spot, full) << "column " << x << " inside the inner cone";
      ++inside;
    } else if (angle > outer + 0.01f) {
      EXPECT_EQ(spot, 0.0f) << "column " << x << " outside the outer cone";
      ++outside;
    } else if (angle > inner + 0.02f && angle < outer - 0.08f) {
      EXPECT_GT(spot, 0.0f) << "column " << x << " between the cones";
      EXPECT_LT(spot, full) << "column " << x << " between the cones";
      ++between;
    }
  }
  EXPECT_GT(inside, 10);
  EXPECT_GT(outside, 10);
  EXPECT_GT(between, 3);
}

TEST(Lights, RangeWindowCutsOffAtTheRange) {
  const float height = 1.0f, range = 2.0f;
  Scene scene = planeScene();
  scene.lights.push_back(Light::point({0, 0, height}, float3(1.0f), 0.8f, range));
  const Frame frame = renderPlane(scene);
  const int row = kSize / 2;
  int lit = 0, dark = 0;
  for (int x = 0; x < kSize; ++x) {
    const float r = std::fabs(worldX(x));
    const float d = std::sqrt(r * r + height * height);
    const float value = linearRed(frame, x, row);
    if (d > range + 0.05f) {
      EXPECT_EQ(value, 0.0f) << "column " << x << " is beyond the range";
      ++dark;
    } else if (d < range - 0.3f) {
      // 1 - (d / range)^4 of the unwindowed light, times the incidence cosine.
      const float expected = 0.8f / (d * d) * (height / d) * (1 - std::pow(d / range, 4.0f));
      EXPECT_NEAR(value, expected, 0.03f * expected + 0.002f) << "column " << x;
      ++lit;
    }
  }
  EXPECT_GT(lit, 20);
  EXPECT_GT(dark, 20);
}

TEST(Lights, TwoLightsAreTheSumOfEach) {
  const Light a = Light::point({-1.5f, 0.5f, 1.5f}, {1.0f, 0.6f, 0.3f}, 1.2f);
  const Light b = Light::spot({1.0f, -1.0f, 2.0f}, normalize(float3{-0.3f, 0.2f, -1}),
                              {0.3f, 0.5f, 1.0f}, 2.5f, 0.3f, 0.6f);
  Scene sa = planeScene(), sb = planeScene(), both = planeScene();
  sa.lights = {a};
  sb.lights = {b};
  both.lights = {a, b};
  const Frame fa = renderPlane(sa), fb = renderPlane(sb), fab = renderPlane(both);
  double worst = 0;
  int summed = 0;
  for (size_t i = 0; i < fab.color.size(); ++i)
    for (int c = 0; c < 24; c += 8) {
      const float la = decodeSrgb8(static_cast<uint8_t>(fa.color[i] >> c));
      const float lb = decodeSrgb8(static_cast<uint8_t>(fb.color[i] >> c));
      const float lab = decodeSrgb8(static_cast<uint8_t>(fab.color[i] >> c));
      if (la + lb >= 1.0f) continue;  // clipped at white
      // Three 8-bit roundings: a relative 1% each, and a step near black.
      worst = std::max(
          worst, std::fabs(static_cast<double>(lab - (la + lb))) / (0.03 * (la + lb) + 0.003));
      summed += la > 0.01f && lb > 0.01f;
    }
  EXPECT_LE(worst, 1.0);
  EXPECT_GT(summed, 100) << "the two lights should overlap somewhere";
}

TEST(Lights, DirectionalIntensityScalesLikeColour) {
  // Intensity 1 with colour c and intensity 2 with colour c / 2 are the same light.
  Scene one = planeScene(), two = planeScene();
  one.lights = {Light::directional(normalize(float3{0.3f, 0.2f, -1}), float3(0.6f), 1.0f)};
  two.lights = {Light::directional(normalize(float3{0.3f, 0.2f, -1}), float3(0.3f), 2.0f)};
  EXPECT_EQ(renderPlane(one).color, renderPlane(two).color);
  // A white light of intensity 1 straight onto a white surface gives white (no 1/pi).
  Scene straight = planeScene();
  straight.lights = {Light::directional({0, 0, -1}, float3(1.0f))};
  EXPECT_EQ(renderPlane(straight).color[kSize * kSize / 2] & 0xffffffu, 0xffffffu);
}

TEST(Lights, FlatAndGouraudUseWorldPositions) {
  const Light light = Light::point({-3.0f, -3.0f, 1.0f}, float3(1.0f), 2.0f);
  for (Shading shading : {Shading::kFlat, Shading::kGouraud, Shading::kPhong}) {
    Scene scene = planeScene(shading, 8);
    scene.lights = {light};
    const Frame frame = renderPlane(scene);
    // Nearer the light (bottom-left in world, the image's bottom-left) is brighter.
    const float near_light = linearRed(frame, 8, kSize - 9), far = linearRed(frame, kSize - 9, 8);
    EXPECT_GT(near_light, 4 * far) << "shading " << static_cast<int>(shading);
  }
  // Flat: one colour per triangle, the light at the centroid.
  Scene flat = planeScene(Shading::kFlat, 1);
  flat.lights = {light};
  const Frame frame = renderPlane(flat);
  render::LightRig rig;
  rig.prepare(flat);
  // The triangle (a, b, d) of the one cell: corners (-4,-4), (4,-4), (4,4).
  const float3 centre = float3{4.0f / 3, -4.0f / 3, 0};
  const float expected = render::irradiance(rig, {0, 0, 1}, centre).x;
  EXPECT_EQ(frame.color[static_cast<size_t>((kSize - 20) * kSize + kSize - 20)] & 255u,
            encodeSrgb8(expected));
}

TEST(Lights, SameBitsForEveryInstructionSetAndWorkerCount) {
  for (Shading shading : {Shading::kFlat, Shading::kGouraud, Shading::kPhong}) {
    Scene scene = planeScene(shading, 5);
    scene.ambient = float3(0.05f);
    scene.lights = {Light::point({-1.5f, 0.5f, 1.5f}, {1.0f, 0.6f, 0.3f}, 1.2f, 6.0f),
                    Light::spot({1.0f, -1.0f, 2.0f}, normalize(float3{-0.3f, 0.2f, -1}),
                                {0.3f, 0.5f, 1.0f}, 2.5f, 0.3f, 0.6f),
                    Light::directional(normalize(float3{1, 1, -1}), float3(0.2f))};
    // A tilted plane, so that depth and positions vary over the image.
    scene.objects[0].transform.rotation = quat::fromAxisAngle(normalize(float3{1, 0.3f, 0}), 0.5f);
    const Frame reference = renderPlane(scene, 1, SimdLevel::kScalar);
    for (SimdLevel simd : {SimdLevel::kSse2, SimdLevel::kAvx2, SimdLevel::kAvx512})
      for (int workers : {1, 3})
        EXPECT_EQ(renderPlane(scene, workers, simd).color, reference.color)
            << "shading " << static_cast<int>(shading) << ", simd " << static_cast<int>(simd)
            << ", workers " << workers;
  }
}

TEST(Lights, FramesWithPointAndSpotLightsAllocateNothing) {
  Scene scene = planeScene(Shading::kPhong, 6);
  scene.objects.push_back(scene.objects[0]);
  scene.objects[1].shading = Shading::kGouraud;
  scene.objects[1].transform.translation = {0, 0, -0.5f};
  scene.lights = {Light::point({-1.5f, 0.5f, 1.5f}, float3(1.0f), 1.2f, 6.0f),
                  Light::spot({1.0f, -1.0f, 2.0f}, {0, 0, -1}, float3(1.0f), 2.5f, 0.3f, 0.6f)};
  CpuRenderer renderer(2);
  RenderOptions options;
  options.width = options.height = kSize;
  Frame frame;
  // The light moves frame to frame; one frame has MSAA.
  const size_t allocations = allocationsAfterWarmUp([&] {
    for (int i = 0; i < 3; ++i) {
      scene.lights[0].position.x = -1.5f + 0.5f * static_cast<float>(i);
      options.msaa = i == 2 ? 4 : 1;
      renderer.render(scene, options, frame);
    }
  });
  EXPECT_EQ(allocations, 0u);
}

TEST(Lights, NonlinearProjectionsLightTheSameOnEveryInstructionSet) {
  // The ray path (spherical) shades Phong pixels from the same world positions.
  Scene scene = planeScene(Shading::kPhong, 4);
  scene.camera.view_override.reset();
  scene.camera.projection_override.reset();
  scene.camera.position = {0, -1.0f, 3.0f};
  scene.camera.target = {0, 0, 0};
  scene.camera.fov_y_degrees = 90.0f;
  scene.lights = {
      Light::point({-1.0f, 0.5f, 1.0f}, {1.0f, 0.6f, 0.3f}, 1.2f),
      Light::spot({1.0f, -1.0f, 2.0f}, {0, 0, -1}, {0.3f, 0.5f, 1.0f}, 2.5f, 0.3f, 0.6f)};
  RenderOptions options;
  options.width = 2 * kSize;
  options.height = kSize;
  options.projection = Projection::kSpherical;
  auto renderAt = [&](SimdLevel simd) {
    CpuRenderer renderer(2, simd);
    Frame frame;
    renderer.render(scene, options, frame);
    return frame;
  };
  const Frame reference = renderAt(SimdLevel::kScalar);
  Scene unlit = scene;
  unlit.lights.clear();
  std::swap(scene, unlit);
  const Frame dark = renderAt(SimdLevel::kScalar);
  std::swap(scene, unlit);
  EXPECT_NE(reference.color, dark.color) << "the lights show";
  for (SimdLevel simd : {SimdLevel::kSse2, SimdLevel::kAvx2, SimdLevel::kAvx512})
    EXPECT_EQ(renderAt(simd).color, reference.color) << "simd " << static_cast<int>(simd);
}

// ---- KHR_lights_punctual ----

namespace {

// One triangle and the given lights and light nodes (JSON fragments).
std::string gltfWithLights(const std::string& lights, const std::string& light_nodes,
                           const std::string& roots) {
  // Three float positions: (0,0,0), (1,0,0), (0,1,0).
  const std::string positions = "AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAA";
  return R"({"asset":{"version":"2.0"},"extensionsUsed":["KHR_lights_punctual"],
    "extensions":{"KHR_lights_punctual":{"lights":[)" +
         lights + R"(]}},
    "buffers":[{"byteLength":36,"uri":"data:application/octet-stream;base64,)" +
         positions +
         R"("}],
    "bufferViews":[{"buffer":0,"byteLength":36}],
    "accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3",
                  "min":[0,0,0],"max":[1,1,0]}],
    "meshes":[{"primitives":[{"attributes":{"POSITION":0}}]}],
    "nodes":[{"mesh":0})" +
         light_nodes + R"(],
    "scenes":[{"nodes":[)" +
         roots + "]}]}";
}

io::Model loadLights(const std::string& json) {
  Expected<io::Model> model = io::loadGltfFromMemory(
      std::span(reinterpret_cast<const uint8_t*>(json.data()), json.size()), "lights.gltf");
  EXPECT_TRUE(model.ok()) << (model ? "" : model.error().message);
  return model ? std::move(*model) : io::Model{};
}

bool warned(const io::Model& model, const std::string& text) {
  for (const std::string& w : model.warnings)
    if (w.find(text) != std::string::npos) return true;
  return false;
}

}  // namespace

TEST(GltfLights, ReadsTypesUnitsAndPlacement) {
  const std::string lights =
      R"({"type":"point","color":[1,0.5,0.25],"intensity":20,"range":7},
         {"type":"spot","intensity":5,"spot":{"innerConeAngle":0.2,"outerConeAngle":0.5}},
         {"type":"directional","intensity":3})";
  // A parent translated by (1,2,3) holding the point light; the spot turned 90 degrees about X
  // (its -Z becomes +Y); the sun as is.
  const std::string nodes =
      R"(,{"translation":[1,2,3],"children":[2]},
         {"translation":[0,0,1],"extensions":{"KHR_lights_punctual":{"light":0}}},
         {"rotation":[0.7071068,0,0,0.7071068],"translation":[5,0,0],
          "extensions":{"KHR_lights_punctual":{"light":1}}},
         {"extensions":{"KHR_lights_punctual":{"light":2}}},
         {},{},{})";
  const io::Model model = loadLights(gltfWithLights(lights, nodes, "0,1,3,4,5,6,7"));
  ASSERT_EQ(model.lights.size(), 3u);
  const Light& point = model.lights[0];
  EXPECT_EQ(point.type, LightType::kPoint);
  EXPECT_FLOAT_EQ(point.position.x, 1);
  EXPECT_FLOAT_EQ(point.position.y, 2);
  EXPECT_FLOAT_EQ(point.position.z, 4);
  EXPECT_FLOAT_EQ(point.intensity, 20);
  EXPECT_FLOAT_EQ(point.range, 7);
  EXPECT_FLOAT_EQ(point.color.y, 0.5f);
  const Light& spot = model.lights[1];
  EXPECT_EQ(spot.type, LightType::kSpot);
  EXPECT_FLOAT_EQ(spot.position.x, 5);
  EXPECT_NEAR(spot.direction.x, 0, 1e-6);
  EXPECT_NEAR(spot.direction.y, 1, 1e-6);
  EXPECT_NEAR(spot.direction.z, 0, 1e-6);
  EXPECT_FLOAT_EQ(spot.inner_cone, 0.2f);
  EXPECT_FLOAT_EQ(spot.outer_cone, 0.5f);
  EXPECT_FLOAT_EQ(spot.range, 0);
  const Light& sun = model.lights[2];
  EXPECT_EQ(sun.type, LightType::kDirectional);
  EXPECT_FLOAT_EQ(sun.direction.z, -1);
  EXPECT_FLOAT_EQ(sun.intensity, 3);
}

TEST(GltfLights, BadLightsAreSkippedWithAWarning) {
  const std::string lights =
      R"({"type":"point","intensity":-1},
         {"type":"spot","spot":{"innerConeAngle":0.6,"outerConeAngle":0.5}},
         {"type":"spot","spot":{"innerConeAngle":0.1,"outerConeAngle":2.0}},
         {"type":"area"},
         {"type":"point","range":-3},
         {"type":"point","color":[1,1]})";
  std::string nodes;
  for (int i = 0; i < 7; ++i)
    nodes += R"(,{"extensions":{"KHR_lights_punctual":{"light":)" + std::to_string(i) + "}}}";
  const io::Model model = loadLights(gltfWithLights(lights, nodes, "0,1,2,3,4,5,6,7"));
  // Only the point with the bad range stays, with no range.
  ASSERT_EQ(model.lights.size(), 1u);
  EXPECT_EQ(model.lights[0].range, 0.0f);
  EXPECT_TRUE(warned(model, "light 0: intensity")) << "negative intensity";
  EXPECT_TRUE(warned(model, "light 1: the spot's cone")) << "outer < inner";
  EXPECT_TRUE(warned(model, "light 2: the spot's cone")) << "outer > pi/2";
  EXPECT_TRUE(warned(model, "light 3 has the unknown type \"area\"")) << "unknown type";
  EXPECT_TRUE(warned(model, "light 4: range")) << "negative range";
  EXPECT_TRUE(warned(model, "light 5: color has 2 components")) << "short colour";
  EXPECT_TRUE(warned(model, "node 7 refers to light 6, but the file has 6 lights"));
}

// ---- the CLI ----

#ifdef TESSERA_EXE
TEST(CliLights, BadLightFlagsFailWithoutOutput) {
  const std::filesystem::path folder = test::makeTestFolder("lights-cli");
  test::writeFile(folder / "tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  const std::pair<const char*, const char*> cases[] = {
      {"sun:0,0,-1", "the type must be directional, point or spot"},
      {"point", "point needs a position"},
      {"point:1,2", "position: expected three numbers"},
      {"point:0,0,1:1,1,1:-2", "intensity must be a number >= 0"},
      {"point:0,0,1:1,1,1:2:0", "range must be > 0"},
      {"point:0,0,1:1,-1,1", "colour channels must be >= 0"},
      {"directional:0,0,0", "has no length"},
      {"spot:0,0,1:0,0,-1:40,30", "0 <= INNER < OUTER <= 90"},
      {"spot:0,0,1:0,0,-1:10,95", "0 <= INNER < OUTER <= 90"},
      {"spot:0,0,1:0,0,-1", "spot needs"},
      {"directional:0,0,-1:1,1,1:1:5", "too many ':' fields"},
  };
  for (const auto& [value, message] : cases) {
    const test::RunResult r = test::runInFolder(
        folder, TESSERA_EXE, std::string("render tri.obj -o out.png --light '") + value + "'");
    EXPECT_EQ(r.exit_code, 2) << value;
    EXPECT_NE(r.err.find(message), std::string::npos) << value << ": " << r.err;
    EXPECT_FALSE(std::filesystem::exists(folder / "out.png")) << value;
  }
  // A good one renders, and differs from the default rig.
  const test::RunResult lit = test::runInFolder(
      folder, TESSERA_EXE,
      "render tri.obj -o lit.png --resolution 64,48 --light point:0.3,0.3,1:1,0.2,0.2:0.5 --crc");
  const test::RunResult rig =
      test::runInFolder(folder, TESSERA_EXE, "render tri.obj -o rig.png --resolution 64,48 --crc");
  EXPECT_EQ(lit.exit_code, 0) << lit.err;
  EXPECT_EQ(rig.exit_code, 0) << rig.err;
  EXPECT_TRUE(std::filesystem::exists(folder / "lit.png"));
  EXPECT_NE(lit.out, rig.out);
  std::filesystem::remove_all(folder);
}
#endif
