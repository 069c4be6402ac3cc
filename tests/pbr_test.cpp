// The metallic-roughness BRDF (render/pbr.h) against what its formulas must satisfy: energy
// conservation (white furnace), a normalized distribution, Fresnel's limits, a mirror at zero
// roughness, and closed forms at chosen angles.
#include "render/pbr.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <memory>

#include <tessera/math/quat.h>
#include <tessera/scene/color.h>
#include <tessera/scene/primitives.h>
#include <tessera/scene/tangents.h>

#include "environment_test_scenes.h"
#include "render_test_scenes.h"

namespace tessera::render {
namespace {

constexpr double kPiD = 3.14159265358979323846;

float3 fromAngles(double theta, double phi) {
  return {static_cast<float>(std::sin(theta) * std::cos(phi)),
          static_cast<float>(std::sin(theta) * std::sin(phi)), static_cast<float>(std::cos(theta))};
}

// The integral of f(l, v) cos(theta_l) over the hemisphere around n = +Z (green channel), by the
// midpoint rule in (theta, phi).
double directionalAlbedo(const PbrSurface& s, float3 v, int theta_steps, int phi_steps) {
  const float3 n{0, 0, 1};
  const double dtheta = 0.5 * kPiD / theta_steps, dphi = 2.0 * kPiD / phi_steps;
  double sum = 0.0;
  for (int i = 0; i < theta_steps; ++i) {
    const double theta = (i + 0.5) * dtheta;
    for (int j = 0; j < phi_steps; ++j) {
      const float3 l = fromAngles(theta, (j + 0.5) * dphi);
      sum += double(pbrBrdf(s, n, v, l).y) * std::cos(theta) * std::sin(theta);
    }
  }
  return sum * dtheta * dphi;
}

TEST(Pbr, WhiteFurnaceReflectsAtMostTheIncomingEnergy) {
  // Pure specular (a white metal: F = 1): single scattering loses energy at high roughness (no
  // multiple bounces), never gains any, at every view angle.
  PbrSurface metal;
  metal.base_color = {1, 1, 1};
  metal.metallic = 1.0f;
  // A white dielectric: the specification's mix weights the diffuse by 1 - F(v.h) per microfacet,
  // not by the specular's directional albedo, so it conserves energy up to moderate view angles
  // only (at 80 degrees it returns up to 22% more at roughness 0.3): tested up to 45 degrees.
  PbrSurface white = metal;
  white.metallic = 0.0f;
  for (float roughness : {0.3f, 0.5f, 0.75f, 1.0f}) {
    metal.roughness = white.roughness = roughness;
    for (double view_degrees : {0.0, 30.0, 45.0, 60.0, 80.0}) {
      const float3 v = fromAngles(view_degrees * kPiD / 180.0, 0.3);
      const double specular = directionalAlbedo(metal, v, 300, 600);
      EXPECT_LE(specular, 1.002) << "roughness " << roughness << ", view " << view_degrees;
      EXPECT_GE(specular, 0.3) << "roughness " << roughness << ", view " << view_degrees;
      if (view_degrees > 45.0) continue;
      const double albedo = directionalAlbedo(white, v, 300, 600);
      EXPECT_LE(albedo, 1.002) << "roughness " << roughness << ", view " << view_degrees;
      EXPECT_GE(albedo, 0.95) << "roughness " << roughness << ", view " << view_degrees;
    }
  }
  // At alpha = 1 and v = n the specular albedo has a closed form: 1 - ln 2.
  metal.roughness = 1.0f;
  EXPECT_NEAR(directionalAlbedo(metal, {0, 0, 1}, 2000, 8), 1.0 - std::log(2.0), 1e-4);
}

TEST(Pbr, DistributionIntegratesToOneOverTheProjectedHemisphere) {
  for (float roughness : {0.05f, 0.1f, 0.3f, 0.6f, 1.0f}) {
    const float alpha = roughness * roughness;
    const float a2 = alpha * alpha;
    // D depends on theta_h only: 2 pi \int D(cos theta) cos theta sin theta dtheta.
    const int steps = 200000;
    const double dtheta = 0.5 * kPiD / steps;
    double sum = 0.0;
    for (int i = 0; i < steps; ++i) {
      const double theta = (i + 0.5) * dtheta;
      sum += double(ggxDistribution(a2, static_cast<float>(std::cos(theta)))) * std::cos(theta) *
             std::sin(theta);
    }
    EXPECT_NEAR(2.0 * kPiD * sum * dtheta, 1.0, 2e-3) << "roughness " << roughness;
  }
  EXPECT_EQ(ggxDistribution(0.25f, -0.1f), 0.0f);  // below the horizon: no microfacets
}

TEST(Pbr, FresnelIsF0AtNormalIncidenceAndOneAtGrazing) {
  EXPECT_EQ(schlickWeight(1.0f), 0.0f);
  EXPECT_EQ(schlickWeight(0.0f), 1.0f);
  EXPECT_NEAR(schlickWeight(0.5f), 1.0f / 32.0f, 1e-7f);
  // v = l = n: h = n, so F = f0 and f = F D V with D = 1 / (pi alpha^2), V = 1 / 4.
  PbrSurface metal;
  metal.base_color = {0.9f, 0.6f, 0.3f};
  metal.metallic = 1.0f;
  metal.roughness = 0.5f;
  const float3 n{0, 0, 1};
  const float3 f = pbrBrdf(metal, n, n, n);
  const double alpha = 0.25, dv = 1.0 / (kPiD * alpha * alpha) * 0.25;
  EXPECT_NEAR(f.x / dv, 0.9, 1e-5);
  EXPECT_NEAR(f.y / dv, 0.6, 1e-5);
  EXPECT_NEAR(f.z / dv, 0.3, 1e-5);
  // A dielectric: F0 = 0.04, and the diffuse gets the rest: (1 - 0.04) c / pi.
  PbrSurface plastic;
  plastic.base_color = {0.5f, 0.5f, 0.5f};
  plastic.roughness = 0.5f;
  EXPECT_NEAR(pbrBrdf(plastic, n, n, n).x, 0.04 * dv + 0.96 * 0.5 / kPiD, 1e-5);
}

TEST(Pbr, ClosedFormAtAnOffSpecularAngle) {
  // n = +Z, v and l 60 degrees apart in the x-z plane at 20 and 40 degrees: h at 30 degrees.
  PbrSurface s;
  s.base_color = {0.2f, 0.4f, 0.8f};
  s.metallic = 0.3f;
  s.roughness = 0.7f;
  const double tv = 20.0 * kPiD / 180.0, tl = -40.0 * kPiD / 180.0;
  const float3 v = fromAngles(tv, 0.0), l = fromAngles(tl, 0.0);
  const double nv = std::cos(tv), nl = std::cos(tl), nh = std::cos((tv + tl) / 2.0);
  const double vh = std::cos((tv - tl) / 2.0);
  const double a = 0.49, a2 = a * a;
  const double d = a2 / (kPiD * std::pow(nh * nh * (a2 - 1.0) + 1.0, 2.0));
  const double vis =
      0.5 / (nl * std::sqrt(nv * nv * (1 - a2) + a2) + nv * std::sqrt(nl * nl * (1 - a2) + a2));
  const float3 f = pbrBrdf(s, {0, 0, 1}, v, l);
  const double base[3] = {0.2, 0.4, 0.8};
  const float got[3] = {f.x, f.y, f.z};
  for (int c = 0; c < 3; ++c) {
    const double f0 = 0.04 * 0.7 + base[c] * 0.3;
    const double fresnel = f0 + (1.0 - f0) * std::pow(1.0 - vh, 5.0);
    const double want = (1.0 - fresnel) * base[c] * 0.7 / kPiD + fresnel * d * vis;
    EXPECT_NEAR(got[c], want, 1e-5 * want) << "channel " << c;
  }
  EXPECT_EQ(pbrBrdf(s, {0, 0, 1}, v, fromAngles(kPiD * 0.6, 0.0)).x, 0.0f);  // l below
}

TEST(Pbr, SmoothMetalIsAMirror) {
  // White metal at the smallest roughness, viewed at 45 degrees: the lobe holds the whole
  // reflection within a few degrees of the mirror direction.
  PbrSurface mirror;
  mirror.base_color = {1, 1, 1};
  mirror.metallic = 1.0f;
  mirror.roughness = 0.0f;
  const float3 n{0, 0, 1};
  const double tv = 45.0 * kPiD / 180.0;
  const float3 v = fromAngles(tv, 0.0);
  // Polar coordinates (psi, phi) around the mirror direction r = (-sin tv, 0, cos tv).
  const double sx = -std::sin(tv), sz = std::cos(tv);
  auto around = [&](double psi, double phi) {
    // r rotated by psi towards the frame (e1 = (cos tv, 0, sin tv), e2 = (0, 1, 0)).
    const double c = std::cos(psi), s = std::sin(psi);
    return float3{static_cast<float>(sx * c + std::cos(tv) * s * std::cos(phi)),
                  static_cast<float>(s * std::sin(phi)),
                  static_cast<float>(sz * c + std::sin(tv) * s * std::cos(phi))};
  };
  const double cone = 3.0 * kPiD / 180.0;
  const int steps = 2000, turns = 256;
  double inside = 0.0;
  for (int i = 0; i < steps; ++i) {
    const double psi = (i + 0.5) * cone / steps;
    for (int j = 0; j < turns; ++j) {
      const float3 l = around(psi, (j + 0.5) * 2.0 * kPiD / turns);
      inside += double(pbrBrdf(mirror, n, v, l).x) * double(l.z) * std::sin(psi);
    }
  }
  inside *= (cone / steps) * (2.0 * kPiD / turns);
  EXPECT_GT(inside, 0.95);
  EXPECT_LT(inside, 1.02);
  // Ten degrees off the mirror direction nothing is reflected.
  const float3 off = around(10.0 * kPiD / 180.0, 1.0);
  EXPECT_LT(pbrBrdf(mirror, n, v, off).x * off.z, 1e-3f);
  // A rough metal spreads the same energy: far less at the mirror direction.
  PbrSurface rough = mirror;
  rough.roughness = 0.6f;
  EXPECT_LT(pbrBrdf(rough, n, v, around(0.0, 0.0)).x * 100.0f,
            pbrBrdf(mirror, n, v, around(0.0, 0.0)).x);
}

TEST(Pbr, AmbientOfAWhiteDielectricIsTheEnvironmentAndAMirrorReflectsIt) {
  const float3 ambient{0.3f, 0.5f, 0.7f};
  PbrSurface white;
  white.base_color = {1, 1, 1};
  for (float roughness : {0.0f, 0.4f, 1.0f})
    for (float nv : {0.05f, 0.5f, 1.0f}) {
      white.roughness = roughness;
      const float3 a = pbrAmbient(pbrLobes(white), ambient, 1.0f, nv);
      EXPECT_NEAR(a.x, 0.3f, 1e-6f);
      EXPECT_NEAR(a.z, 0.7f, 1e-6f);
    }
  PbrSurface metal;
  metal.base_color = {0.95f, 0.6f, 0.2f};
  metal.metallic = 1.0f;
  metal.roughness = 0.0f;
  // Head-on, a smooth metal reflects the environment times F0 (its base colour).
  const float3 head_on = pbrAmbient(pbrLobes(metal), {1, 1, 1}, 1.0f, 1.0f);
  EXPECT_NEAR(head_on.x, 0.95f, 1e-6f);
  EXPECT_NEAR(head_on.z, 0.2f, 1e-6f);
  // At grazing angles towards white; occlusion scales the whole term.
  EXPECT_GT(pbrAmbient(pbrLobes(metal), {1, 1, 1}, 1.0f, 0.05f).z, 0.6f);
  EXPECT_NEAR(pbrAmbient(pbrLobes(metal), {1, 1, 1}, 0.25f, 1.0f).x, 0.25f * 0.95f, 1e-6f);
}

TEST(Pbr, ShadesLightsAtTesserasExposure) {
  // A rough white dielectric lit head-on by irradiance 1 and seen head-on: (1 - F) + F pi D V
  // = 0.96 + 0.04 * 0.25 (D = 1 / pi, V = 1 / 4 at alpha = 1), plus the ambient, plus emission.
  LightRig rig;
  rig.ambient = {0.1f, 0.1f, 0.1f};
  rig.eye = {0, 0, 10};
  rig.lights.push_back(shadeLight(Light::directional({0, 0, -1}, {1, 1, 1}, 1.0f)));
  PbrSurface white;
  white.base_color = {1, 1, 1};
  white.emissive = {0.0f, 0.0f, 0.5f};
  const float3 c = shadePbr(rig, white, {0, 0, 1}, {0, 0, 0});
  EXPECT_NEAR(c.x, 0.97f + 0.1f, 1e-5f);
  EXPECT_NEAR(c.z, 0.97f + 0.1f + 0.5f, 1e-5f);
  // A point light at distance 2 straight above: irradiance intensity / 4.
  rig.lights = {shadeLight(Light::point({0, 0, 2}, {1, 1, 1}, 4.0f))};
  rig.ambient = {0, 0, 0};
  white.emissive = {0, 0, 0};
  EXPECT_NEAR(shadePbr(rig, white, {0, 0, 1}, {0, 0, 0}).y, 0.97f, 1e-5f);
  // Behind the surface: nothing.
  rig.lights = {shadeLight(Light::directional({0, 0, 1}, {1, 1, 1}, 1.0f))};
  EXPECT_EQ(shadePbr(rig, white, {0, 0, 1}, {0, 0, 0}).y, 0.0f);
}

// ---- Shading::kPbr in the renderer ----

// A w x h texture of one linear (or sRGB) RGBA8 texel everywhere.
std::shared_ptr<Texture> flatTexture(uint8_t r, uint8_t g, uint8_t b, bool srgb) {
  auto t = std::make_shared<Texture>();
  t->width = t->height = 2;
  t->srgb = srgb;
  t->texels.assign(4, uint32_t{r} | uint32_t{g} << 8 | uint32_t{b} << 16 | 0xff000000u);
  return t;
}

// A square filling most of a clip-space view (the camera at infinity along +Z), facing +Z, with
// normals, UVs (u along `u_axis`, v along `v_axis`, each +-1 for x or y) and generated tangents.
Object pbrQuad(float2 u_axis, float2 v_axis) {
  Mesh m;
  m.positions = {{-0.8f, -0.8f, 0}, {0.8f, -0.8f, 0}, {0.8f, 0.8f, 0}, {-0.8f, 0.8f, 0}};
  m.normals.assign(4, float3{0, 0, 1});
  for (const float3& p : m.positions)
    m.uvs.push_back({0.5f + 0.5f * (u_axis.x * p.x + u_axis.y * p.y),
                     0.5f + 0.5f * (v_axis.x * p.x + v_axis.y * p.y)});
  m.indices = {0, 1, 2, 0, 2, 3};
  generateTangents(m);
  Object o;
  o.mesh = std::make_shared<Mesh>(m);
  o.shading = Shading::kPbr;
  o.cull = CullMode::kNone;
  Material& material = o.materials[0];
  material.base_color = {0.8f, 0.6f, 0.4f, 1.0f};
  material.metallic = 0.3f;
  material.roughness = 0.45f;
  for (TextureSlot* slot :
       {&material.normal, &material.metallic_roughness, &material.occlusion, &material.emissive})
    slot->sampler.filter = TextureFilter::kBilinear;
  return o;
}

Scene pbrQuadScene(const Object& quad) {
  Scene scene = test::clipSpaceScene();
  scene.ambient = {0.1f, 0.1f, 0.1f};
  scene.lights.push_back(Light::directional(normalize(float3{-0.5f, -0.3f, -1.0f}), {1, 1, 1}));
  scene.lights.push_back(Light::point({0.3f, 0.2f, 0.6f}, {1.0f, 0.8f, 0.6f}, 0.2f));
  scene.objects.push_back(quad);
  return scene;
}

int maxDifference(const Frame& a, const Frame& b) {
  int most = 0;
  for (size_t i = 0; i < a.color.size(); ++i)
    for (int c = 0; c < 24; c += 8)
      most =
          std::max(most, std::abs(int((a.color[i] >> c) & 0xff) - int((b.color[i] >> c) & 0xff)));
  return most;
}

TEST(PbrShading, NormalMapShadesAFlatQuadAsTheTiltedNormalWould) {
  // A tangent-space tilt of (0.3, -0.2, 1) (normalized), 8-bit encoded.
  const float3 tilt = normalize(float3{0.3f, -0.2f, 1.0f});
  auto code = [](float x) { return static_cast<uint8_t>(std::lround((x * 0.5f + 0.5f) * 255.0f)); };
  const uint8_t r = code(tilt.x), g = code(tilt.y), b = code(tilt.z);
  const float3 decoded{r / 255.0f * 2.0f - 1.0f, g / 255.0f * 2.0f - 1.0f,
                       b / 255.0f * 2.0f - 1.0f};
  // UVs along x and y; turned a quarter; mirrored in u (a left-handed tangent frame): the tilt
  // lands along tangent and bitangent, whichever way they lie in the world.
  struct Layout {
    float2 u, v;
    float3 world_tilt;  // t x + b y + n z for that layout
  };
  const Layout layouts[] = {
      {{1, 0}, {0, 1}, {decoded.x, decoded.y, decoded.z}},
      {{0, 1}, {-1, 0}, {-decoded.y, decoded.x, decoded.z}},
      {{-1, 0}, {0, 1}, {-decoded.x, decoded.y, decoded.z}},
  };
  for (const Layout& layout : layouts) {
    Object mapped = pbrQuad(layout.u, layout.v);
    mapped.materials[0].normal.texture = flatTexture(r, g, b, false);
    Object tilted = pbrQuad(layout.u, layout.v);
    auto mesh = std::make_shared<Mesh>(*tilted.mesh);
    mesh->normals.assign(4, normalize(layout.world_tilt));
    tilted.mesh = mesh;
    const Frame a = test::renderScene(pbrQuadScene(mapped), 96, 96);
    const Frame want = test::renderScene(pbrQuadScene(tilted), 96, 96);
    const Frame flat = test::renderScene(pbrQuadScene(pbrQuad(layout.u, layout.v)), 96, 96);
    EXPECT_GT(test::coveredCount(a), 96 * 96 / 2);
    EXPECT_LE(maxDifference(a, want), 1) << "u " << layout.u.x << "," << layout.u.y;
    EXPECT_GT(maxDifference(a, flat), 8) << "the tilt shows";
  }
}

TEST(PbrShading, MapsReadTheirChannelsAndMultiplyTheFactors) {
  // metallicRoughness: G roughness, B metallic; occlusion: R; emissive: sRGB RGB.
  Object mapped = pbrQuad({1, 0}, {0, 1});
  Material& m = mapped.materials[0];
  m.metallic = 0.8f;
  m.roughness = 0.9f;
  m.metallic_roughness.texture = flatTexture(7, 128, 200, false);
  m.occlusion.texture = flatTexture(100, 3, 250, false);
  m.occlusion_strength = 0.75f;
  m.emissive.texture = flatTexture(188, 60, 20, true);
  m.emissive_factor = {0.5f, 1.0f, 2.0f};
  Object factors = pbrQuad({1, 0}, {0, 1});
  Material& f = factors.materials[0];
  f.metallic = 0.8f * (200 / 255.0f);
  f.roughness = 0.9f * (128 / 255.0f);
  f.occlusion.texture = flatTexture(255, 0, 0, false);  // ambient x 1: the strength applied below
  f.emissive_factor = {0.5f * decodeSrgb8(188), decodeSrgb8(60), 2.0f * decodeSrgb8(20)};
  Scene with_maps = pbrQuadScene(mapped), with_factors = pbrQuadScene(factors);
  with_factors.ambient = with_maps.ambient * (1.0f + 0.75f * (100 / 255.0f - 1.0f));
  const Frame a = test::renderScene(with_maps, 64, 64), b = test::renderScene(with_factors, 64, 64);
  EXPECT_GT(test::coveredCount(a), 64 * 64 / 2);
  EXPECT_LE(maxDifference(a, b), 1);
  // Each map matters: without them the picture changes.
  EXPECT_GT(maxDifference(a, test::renderScene(pbrQuadScene(pbrQuad({1, 0}, {0, 1})), 64, 64)), 8);
}

// A PBR scene with every kind of light, maps, clipped triangles, and several objects per tile.
// The camera at (0, 1, 4) and a light of every kind: a sun, a point and a spot.
Scene everyLightScene() {
  Scene scene;
  scene.camera.position = {0, 1, 4};
  scene.camera.near_z = 0.3f;
  scene.lights.push_back(Light::directional(normalize(float3{-1, -2, -1}), {0.9f, 0.9f, 0.9f}));
  scene.lights.push_back(Light::point({1, 1, 1}, {1, 0.5f, 0.2f}, 2.0f, 6.0f));
  scene.lights.push_back(Light::spot({-1, 2, 1}, normalize(float3{0.5f, -1, -0.5f}),
                                     {0.2f, 0.5f, 1}, 4.0f, 0.2f, 0.6f));
  return scene;
}

Scene pbrStressScene() {
  Scene scene = everyLightScene();
  Mesh sphere = makeUvSphere(64, 32);
  generateTangents(sphere);
  Object ball;
  ball.mesh = std::make_shared<Mesh>(sphere);
  ball.shading = Shading::kPbr;
  Material& m = ball.materials[0];
  m.metallic = 0.7f;
  m.roughness = 0.35f;
  auto checker = std::make_shared<Texture>();
  checker->width = checker->height = 16;
  checker->srgb = false;
  for (int i = 0; i < 256; ++i)
    checker->texels.push_back(((i + i / 16) % 2 ? 0xff80c060u : 0xff4020a0u) + uint32_t(i));
  generateMipmaps(*checker);
  m.metallic_roughness.texture = checker;
  m.normal.texture = checker;
  m.occlusion.texture = checker;
  m.emissive.texture = flatTexture(30, 10, 5, true);
  m.emissive_factor = {1, 1, 1};
  m.albedo = checker;
  scene.objects.push_back(ball);
  Object floor = pbrQuad({1, 0}, {0, 1});
  floor.transform.rotation = fromEuler({-1.5707963f, 0, 0});
  floor.transform.scale = float3(40.0f);
  floor.transform.translation = {0, -1, 0};
  floor.materials[0].normal.texture = checker;
  floor.materials[0].metallic_roughness.texture = checker;
  floor.materials[0].metallic_roughness.sampler.filter = TextureFilter::kTrilinear;
  scene.objects.push_back(floor);
  Object small = ball;
  small.transform.scale = float3(0.05f);
  for (int i = 0; i < 30; ++i) {
    small.transform.translation = {-1.5f + 0.1f * i, 0.8f, 0.5f};
    scene.objects.push_back(small);
  }
  return scene;
}

TEST(PbrShading, ImageIsBitIdenticalForEverySimdLevelWorkerCountAndWithMsaa) {
  const Scene scene = pbrStressScene();
  for (int msaa : {1, 4}) {
    RenderOptions options;
    options.width = 233;
    options.height = 171;
    options.msaa = msaa;
    options.normals = true;
    const Frame scalar = test::renderAt(scene, options, SimdLevel::kScalar, 1);
    EXPECT_GT(test::coveredCount(scalar), 233 * 171 / 2);
    for (SimdLevel level :
         {SimdLevel::kSse2, SimdLevel::kAvx2, SimdLevel::kAvx512, SimdLevel::kAuto})
      for (int workers : {1, 3}) {
        const Frame other = test::renderAt(scene, options, level, workers);
        EXPECT_EQ(scalar.color, other.color) << int(level) << ", " << workers << ", msaa " << msaa;
        EXPECT_EQ(0, std::memcmp(scalar.normal.data(), other.normal.data(),
                                 scalar.normal.size() * sizeof(float3)));
      }
  }
}

// Eight pixels of several triangles lit per pixel without maps (PBR of one material, or Phong)
// take one evaluation of the lights for the eight (shadeLitMixed); with the normal AOV on they are
// shaded triangle by triangle. Both give the same bits: spheres of small triangles under every
// kind of light, with shadows, vertex colours and emission, tone mapping on and off, 1 and 4
// samples.
TEST(PbrShading, TrianglesLitAlikeShareOneEvaluationWithTheSameBits) {
  Scene scene = everyLightScene();
  Mesh sphere = makeUvSphere(96, 48);
  for (size_t i = 0; i < sphere.positions.size(); ++i)
    sphere.colors.push_back({0.5f + 0.5f * sphere.positions[i].x, 0.8f, 0.6f, 1.0f});
  Object pbr;
  pbr.mesh = std::make_shared<Mesh>(sphere);
  pbr.shading = Shading::kPbr;
  pbr.transform.translation = {-0.9f, 0, 0};
  pbr.materials[0].metallic = 0.6f;
  pbr.materials[0].roughness = 0.3f;
  pbr.materials[0].emissive_factor = {0.05f, 0.02f, 0.0f};
  scene.objects.push_back(pbr);
  Object phong = pbr;
  phong.shading = Shading::kPhong;
  phong.transform.translation = {0.9f, 0, 0};
  scene.objects.push_back(phong);
  Mesh floor;
  floor.positions = {{-30, -1, 20}, {30, -1, 20}, {30, -1, -60}, {-30, -1, -60}};
  floor.indices = {0, 1, 2, 0, 2, 3};
  Object floor_object = pbr;
  floor_object.mesh = std::make_shared<Mesh>(floor);
  floor_object.transform.translation = {0, 0, 0};
  scene.objects.push_back(floor_object);
  RenderOptions options;
  options.width = 233;
  options.height = 151;
  options.shadows.enabled = true;
  options.shadows.map_size = 512;
  test::expectMixedShadingMatchesPerTriangle(scene, options);
}

TEST(PbrShading, PixelMatchesTheScalarReference) {
  // An untextured quad without maps: each pixel is shadePbr of its interpolated inputs; the
  // eight-lane code does the same operations.
  Scene scene = pbrQuadScene(pbrQuad({1, 0}, {0, 1}));
  scene.camera = {};
  scene.camera.position = {0.2f, 0.3f, 2.5f};
  RenderOptions options;
  options.width = options.height = 48;
  const Frame frame = test::renderAt(scene, options, SimdLevel::kAuto, 1);
  LightRig rig;
  rig.prepare(scene);
  PbrSurface s;
  s.base_color = scene.objects[0].materials[0].base_color.xyz();
  s.metallic = 0.3f;
  s.roughness = 0.45f;
  // The centre pixel's world point, from the triangle id's plane (z = 0) and the pixel's ray.
  const float4x4 inv = inverse(scene.camera.projection(1.0f) * scene.camera.view());
  int compared = 0;
  for (int y = 4; y < 48; y += 9)
    for (int x = 4; x < 48; x += 9) {
      const size_t i = size_t(y) * 48 + size_t(x);
      if (frame.triangle_id[i] == kNoTriangle) continue;
      const float nx = (x + 0.5f) / 24.0f - 1.0f, ny = 1.0f - (y + 0.5f) / 24.0f;
      const float4 a = inv * float4{nx, ny, -1, 1}, b = inv * float4{nx, ny, 1, 1};
      const float3 p0 = a.xyz() / a.w, p1 = b.xyz() / b.w;
      const float3 p = p0 + (p1 - p0) * (p0.z / (p0.z - p1.z));
      const float3 c = shadePbr(rig, s, {0, 0, 1}, p);
      const uint32_t want = packSrgba8(float4(c, 1.0f));
      for (int k = 0; k < 24; k += 8)
        EXPECT_NEAR(int((frame.color[i] >> k) & 0xff), int((want >> k) & 0xff), 1) << x << "," << y;
      ++compared;
    }
  EXPECT_GT(compared, 10);
}

// ---- Environment light (--hdri) ----

using test::skyEnvironment;

// The white furnace: a white, rough dielectric under a uniform white environment returns
// at most what comes in (and nearly all of it: it is white), from every side; a smooth white metal
// reflects the environment.
TEST(PbrEnvironment, WhiteFurnaceAndAMetalMirror) {
  Scene scene;
  scene.environment = skyEnvironment({1, 1, 1}, {1, 1, 1});
  scene.camera.position = {0, 0, 10};
  LightRig rig;
  rig.prepare(scene);
  ASSERT_NE(rig.environment, nullptr);
  PbrSurface rough;
  rough.roughness = 1.0f;
  for (float3 n : {float3{0, 0, 1}, normalize(float3{1, 0, 1}), normalize(float3{0, 1, 0.2f}),
                   normalize(float3{-1, -2, 0.5f})}) {
    const float3 c = shadePbr(rig, rough, n, {0, 0, 0});
    EXPECT_LE(c.x, 1.0f + 2e-3f) << n.x << "," << n.y << "," << n.z;
    EXPECT_GT(c.x, 0.9f);
  }
  // A mirror-like metal in a sky over black ground: the sky where its reflection points up, the
  // ground where it points down.
  scene.environment = skyEnvironment({1, 1, 1}, {0, 0, 0});
  rig.prepare(scene);
  PbrSurface metal;
  metal.metallic = 1.0f;
  metal.roughness = 0.0f;
  const float3 up_facing = normalize(float3{0, 1, 1});     // v = +Z reflects to +Y
  const float3 down_facing = normalize(float3{0, -1, 1});  // ... to -Y
  EXPECT_GT(shadePbr(rig, metal, up_facing, {0, 0, 0}).x, 0.95f);
  EXPECT_LT(shadePbr(rig, metal, down_facing, {0, 0, 0}).x, 0.05f);
  // Without the environment the uniform ambient is back.
  scene.environment = nullptr;
  scene.ambient = {0, 0, 0};
  rig.prepare(scene);
  EXPECT_EQ(shadePbr(rig, metal, up_facing, {0, 0, 0}).x, 0.0f);
}

TEST(PbrEnvironment, LitImageIsBitIdenticalForEverySimdLevelAndMatchesTheReference) {
  Scene scene = pbrQuadScene(pbrQuad({1, 0}, {0, 1}));
  scene.camera = {};
  scene.camera.position = {0.2f, 0.3f, 2.5f};
  scene.environment = skyEnvironment({0.9f, 0.8f, 1.2f}, {0.1f, 0.2f, 0.05f});
  RenderOptions options;
  options.width = options.height = 48;
  const Frame scalar = test::renderAt(scene, options, SimdLevel::kScalar, 1);
  for (SimdLevel level : {SimdLevel::kSse2, SimdLevel::kAvx2, SimdLevel::kAvx512, SimdLevel::kAuto})
    EXPECT_EQ(scalar.color, test::renderAt(scene, options, level, 2).color) << int(level);
  // The environment changes the picture (the sky is brighter than the 0.1 ambient it replaces).
  Scene plain = scene;
  plain.environment = nullptr;
  EXPECT_GT(maxDifference(scalar, test::renderAt(plain, options, SimdLevel::kAuto, 1)), 20);
}

// The environment read eight lanes at a time (environment_lanes.h) against the scalar code of one
// pixel: an image that changes along both axes, the stress scene's rough-mapped metal spheres
// (their lanes fall between different pairs of prefiltered levels), multisampled edges (shaded one
// pixel at a time by the scalar code) and interiors, every SIMD level and worker count.
TEST(PbrEnvironment, VariedImageIsBitIdenticalForEverySimdLevelWorkerCountAndWithMsaa) {
  Scene scene = pbrStressScene();
  EnvironmentImage image;
  image.width = 48;
  image.height = 24;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x)
      image.texels.push_back({0.2f + 0.05f * float((x * 7 + y * 3) % 11), 0.1f * float(y % 5),
                              1.5f - 0.03f * float(x)});
  scene.environment = std::make_shared<const Environment>(std::move(image));
  scene.world_to_environment = toMatrix3(quat::fromAxisAngle(normalize(float3{1, 2, 0}), 0.6f));
  for (int msaa : {1, 4}) {
    RenderOptions options;
    options.width = 161;
    options.height = 117;
    options.msaa = msaa;
    const Frame scalar = test::renderAt(scene, options, SimdLevel::kScalar, 1);
    EXPECT_GT(test::coveredCount(scalar), 161 * 117 / 2);
    for (SimdLevel level :
         {SimdLevel::kSse2, SimdLevel::kAvx2, SimdLevel::kAvx512, SimdLevel::kAuto})
      for (int workers : {1, 3})
        EXPECT_EQ(scalar.color, test::renderAt(scene, options, level, workers).color)
            << int(level) << ", " << workers << ", msaa " << msaa;
  }
}

}  // namespace
}  // namespace tessera::render
