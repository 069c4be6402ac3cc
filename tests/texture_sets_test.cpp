// glTF materials whose textures each have their own textureInfo (issue 19): each map read through
// its own texture coordinate set (TEXCOORD_0 or TEXCOORD_1) and its own KHR_texture_transform, as
// the glTF 2.0 specification and the extension say; bad sets fall back to TEXCOORD_0 with a
// warning; a mirrored double-sided quad shades as the unmirrored one, from a glTF node or as a
// library Object whose mesh keeps its winding.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include <tessera/io/model_loader.h>
#include <tessera/render/cpu_renderer.h>
#include <tessera/scene/graph.h>

#include "gltf_test_files.h"

namespace tessera::io {
namespace {

using namespace gltf_test;  // NOLINT(google-build-using-namespace)

constexpr int kSize = 64;  // the image; the quad fills it exactly

uint32_t rgb(int r, int g, int b) {
  return 0xff000000u | static_cast<uint32_t>(r) | static_cast<uint32_t>(g) << 8 |
         static_cast<uint32_t>(b) << 16;
}

int channel(uint32_t c, int k) {
  return static_cast<int>((c >> (8 * k)) & 255u);
}

std::string imageUri(const std::vector<uint8_t>& png) {
  return "{\"uri\":\"data:image/png;base64," + base64(png) + "\"}";
}

// The tangent-space normal (x, 0, z) as a normal map texel.
uint32_t normalTexel(float x, float z) {
  auto code = [](float c) { return static_cast<int>(std::lround((c * 0.5f + 0.5f) * 255.0f)); };
  return rgb(code(x), 128, code(z));
}

// The quad [-1, 1]^2 in z = 0 facing +z. TEXCOORD_0 puts glTF's uv (0, 0) at the top-left
// corner, so that pixel (x, y) of the image reads uv0 = ((x + 0.5) / kSize, (y + 0.5) / kSize).
// TEXCOORD_1 (when `with_set1`) is set 0 turned a quarter: uv1 = (v0, 1 - u0), so its u grows down
// the image (-y in the world) where set 0's grows to the right (+x).
class TextureSets : public GltfFiles {
 protected:
  // `material` (JSON) over textures 0 .. n-1 of `images` (PNG), nearest filtering.
  Expected<Model> loadQuad(const std::string& material, const std::vector<std::string>& images,
                           bool with_set1 = true, const std::string& node = "{\"mesh\":0}") {
    GltfBuilder b;
    const int p = b.positions(std::vector<float3>{{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}});
    const int n =
        b.accessor(std::vector<float>{0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1}, kFloat, "VEC3", 4);
    const int uv0 = b.accessor(std::vector<float>{0, 1, 1, 1, 1, 0, 0, 0}, kFloat, "VEC2", 4);
    const int uv1 = b.accessor(std::vector<float>{1, 1, 1, 0, 0, 0, 0, 1}, kFloat, "VEC2", 4);
    const int idx = b.accessor(std::vector<uint16_t>{0, 1, 2, 0, 2, 3}, kShort, "SCALAR", 6);
    std::string attributes =
        ",\"NORMAL\":" + std::to_string(n) + ",\"TEXCOORD_0\":" + std::to_string(uv0);
    if (with_set1) attributes += ",\"TEXCOORD_1\":" + std::to_string(uv1);
    std::string textures, image_list;
    for (size_t i = 0; i < images.size(); ++i) {
      textures +=
          (i ? "," : "") + std::string("{\"source\":") + std::to_string(i) + ",\"sampler\":0}";
      image_list += (i ? "," : "") + images[i];
    }
    return loadJson(
        b.json("\"scenes\":[{\"nodes\":[0]}],\"nodes\":[" + node + "]," +
               oneMesh(p, attributes, ",\"indices\":" + std::to_string(idx) + ",\"material\":0") +
               ",\"materials\":[" + material + "],\"textures\":[" + textures + "],\"images\":[" +
               image_list + "],\"samplers\":[{\"magFilter\":9728,\"minFilter\":9728}]" +
               ",\"extensionsUsed\":[\"KHR_texture_transform\"]"));
  }

  // The model's instances, PBR, both faces drawn, seen head on by an orthographic camera whose
  // view the quad fills, without lights or ambient unless given.
  static Frame render(const Model& model, const std::vector<Light>& lights = {},
                      float3 ambient = float3(0.0f)) {
    SceneGraph graph = model.graph;
    graph.updateWorld();
    graph.prepareMeshes();
    Scene scene;
    Object style;
    style.shading = Shading::kPbr;
    style.cull = CullMode::kNone;
    instantiate(graph, style, scene);
    scene.camera.position = {0, 0, 5};
    scene.camera.target = {0, 0, 0};
    scene.camera.orthographic = true;
    scene.camera.ortho_half_height = 1.0f;
    scene.lights = lights;
    scene.ambient = ambient;
    RenderOptions o;
    o.width = o.height = kSize;
    o.normals = true;
    CpuRenderer cpu(1);
    Frame frame;
    cpu.render(scene, o, frame);
    return frame;
  }
};

// A 4x4 texture whose every texel has its own colour: texel (i, j) (column i, row j from the top).
std::vector<uint32_t> labelledTexels() {
  std::vector<uint32_t> texels;
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 4; ++i) texels.push_back(rgb(30 + 60 * i, 30 + 60 * j, 200));
  return texels;
}

// KHR_texture_transform on an emissive map: uv' = T(offset) S(scale) uv with offset (0.5, 0) and
// scale 0.5 (the extension's order and glTF's uv, v down) moves every pixel's read to texel
// (floor(4 (u/2 + 1/2)), floor(4 v/2)). Black dielectric without light: the image is the emission.
TEST_F(TextureSets, EmissiveMapTakesItsOwnTextureTransform) {
  Expected<Model> model = loadQuad(
      "{\"pbrMetallicRoughness\":{\"baseColorFactor\":[0,0,0,1],\"metallicFactor\":0},"
      "\"emissiveFactor\":[1,1,1],\"emissiveTexture\":{\"index\":0,\"extensions\":{"
      "\"KHR_texture_transform\":{\"offset\":[0.5,0],\"scale\":[0.5,0.5]}}}}",
      {imageUri(pngBytes(4, 4, labelledTexels()))});
  ASSERT_TRUE(model) << model.error().message;
  EXPECT_TRUE(model->warnings.empty()) << allWarnings(*model);
  const Frame frame = render(*model);
  const std::vector<uint32_t> texels = labelledTexels();
  int worst = 0;
  for (int y = 0; y < kSize; ++y) {
    for (int x = 0; x < kSize; ++x) {
      const float u = (static_cast<float>(x) + 0.5f) / kSize;
      const float v = (static_cast<float>(y) + 0.5f) / kSize;
      const int i = static_cast<int>(4.0f * (0.5f * u + 0.5f));
      const int j = static_cast<int>(4.0f * (0.5f * v));
      const uint32_t want = texels[static_cast<size_t>(j * 4 + i)];
      const uint32_t got = frame.color[static_cast<size_t>(y * kSize + x)];
      for (int k = 0; k < 3; ++k)
        worst = std::max(worst, std::abs(channel(got, k) - channel(want, k)));
    }
  }
  EXPECT_LE(worst, 1) << "the emission is not the transformed texel's";
}

// The same transform on the occlusion and metallic-roughness maps moves their texels too: an
// occlusion map black in the transformed window's columns 2-3 and white in 0-1 darkens the
// ambient-lit image on the left (where the transformed read lands in columns 2-3) only.
TEST_F(TextureSets, OcclusionMapTakesItsOwnTextureTransform) {
  std::vector<uint32_t> texels;
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 4; ++i) texels.push_back(i < 2 ? rgb(255, 255, 255) : rgb(0, 0, 0));
  Expected<Model> model = loadQuad(
      "{\"pbrMetallicRoughness\":{\"baseColorFactor\":[1,1,1,1],\"metallicFactor\":0},"
      "\"occlusionTexture\":{\"index\":0,\"extensions\":{"
      "\"KHR_texture_transform\":{\"offset\":[0.5,0],\"scale\":[0.5,0.5]}}}}",
      {imageUri(pngBytes(4, 4, texels))});
  ASSERT_TRUE(model) << model.error().message;
  const Frame frame = render(*model, {}, float3(0.5f));
  // u' = u / 2 + 1/2 is in [0.5, 1): columns 2-3, black, everywhere: no ambient anywhere.
  for (int x : {4, 20, 44, 60}) {
    const uint32_t c = frame.color[static_cast<size_t>(32 * kSize + x)];
    EXPECT_EQ(channel(c, 0), 0) << "x " << x << ": the occlusion map's transform is not applied";
  }
}

// A normal map read through TEXCOORD_1 while the base colour reads TEXCOORD_0. Set 1 is set 0
// turned a quarter, so its tangent (the direction of growing u1) points down the image (-y): the
// map's left texel, tilted to tangent-space +x, tilts the normals of the image's top half (u1 <
// 1/2) to world -y, and its right texel those of the bottom half to +y. The base colour, red on
// the left of its texture and green on the right, splits the image left and right.
TEST_F(TextureSets, NormalMapReadsTexcoord1WhileBaseColourReadsTexcoord0) {
  Expected<Model> model = loadQuad(
      "{\"pbrMetallicRoughness\":{\"baseColorTexture\":{\"index\":0,\"texCoord\":0},"
      "\"metallicFactor\":0},\"normalTexture\":{\"index\":1,\"texCoord\":1}}",
      {imageUri(pngBytes(2, 1, {rgb(255, 0, 0), rgb(0, 255, 0)})),
       imageUri(pngBytes(2, 1, {normalTexel(0.6f, 0.8f), normalTexel(-0.6f, 0.8f)}))});
  ASSERT_TRUE(model) << model.error().message;
  EXPECT_TRUE(model->warnings.empty()) << allWarnings(*model);
  const Frame frame = render(*model, {}, float3(0.5f));
  auto normal = [&](int x, int y) { return frame.normal[static_cast<size_t>(y * kSize + x)]; };
  auto color = [&](int x, int y) { return frame.color[static_cast<size_t>(y * kSize + x)]; };
  for (int x : {8, 56}) {
    expectNear3(normal(x, 10), normalize(float3{0.0f, -0.6f, 0.8f}), 0.03f);
    expectNear3(normal(x, 54), normalize(float3{0.0f, 0.6f, 0.8f}), 0.03f);
  }
  for (int y : {10, 54}) {
    EXPECT_GT(channel(color(8, y), 0), channel(color(8, y), 1) + 40) << "left is red";
    EXPECT_GT(channel(color(56, y), 1), channel(color(56, y), 0) + 40) << "right is green";
  }
}

// A texCoord past the two sets, or naming a set the primitive lacks: a warning, and TEXCOORD_0.
TEST_F(TextureSets, AMissingSetFallsBackToTexcoord0WithAWarning) {
  const std::string image = imageUri(pngBytes(4, 4, labelledTexels()));
  Expected<Model> past = loadQuad(
      "{\"pbrMetallicRoughness\":{\"baseColorFactor\":[0,0,0,1],\"metallicFactor\":0},"
      "\"emissiveFactor\":[1,1,1],\"emissiveTexture\":{\"index\":0,\"texCoord\":3}}",
      {image});
  ASSERT_TRUE(past) << past.error().message;
  EXPECT_TRUE(anyWarningContains(*past, "texCoord 3")) << allWarnings(*past);
  EXPECT_EQ(past->materials[0].emissive.sampler.texcoord, 0);

  Expected<Model> missing = loadQuad(
      "{\"pbrMetallicRoughness\":{\"baseColorFactor\":[0,0,0,1],\"metallicFactor\":0},"
      "\"emissiveFactor\":[1,1,1],\"emissiveTexture\":{\"index\":0,\"texCoord\":1}}",
      {image}, /*with_set1=*/false);
  ASSERT_TRUE(missing) << missing.error().message;
  EXPECT_TRUE(anyWarningContains(*missing, "TEXCOORD_1")) << allWarnings(*missing);
  // Drawn as TEXCOORD_0 would draw it: texel (floor(4 u), floor(4 v)).
  const Frame frame = render(*missing);
  const std::vector<uint32_t> texels = labelledTexels();
  for (int y : {5, 40})
    for (int x : {5, 27, 60}) {
      const uint32_t want = texels[static_cast<size_t>((y * 4 / kSize) * 4 + x * 4 / kSize)];
      const uint32_t got = frame.color[static_cast<size_t>(y * kSize + x)];
      for (int k = 0; k < 3; ++k) EXPECT_NEAR(channel(got, k), channel(want, k), 1);
    }
}

// A double-sided quad under a node that mirrors it (scale -1 in x) shades as the unmirrored one
// seen from the same side: its lit side is the one facing the viewer, whatever its winding on
// screen. The light and the quad are symmetric in x, so both images are the same.
TEST_F(TextureSets, MirroredDoubleSidedQuadShadesAsTheUnmirroredOne) {
  const std::string material =
      "{\"doubleSided\":true,\"pbrMetallicRoughness\":{\"baseColorFactor\":[0.8,0.6,0.4,1],"
      "\"metallicFactor\":0,\"roughnessFactor\":0.5}}";
  Expected<Model> plain = loadQuad(material, {}, false);
  Expected<Model> mirrored = loadQuad(material, {}, false, "{\"mesh\":0,\"scale\":[-1,1,1]}");
  ASSERT_TRUE(plain && mirrored);
  const std::vector<Light> lights = {
      Light::directional(normalize(float3{0.0f, -0.5f, -1.0f}), float3(1.0f), 2.0f)};
  const Frame a = render(*plain, lights), b = render(*mirrored, lights);
  const uint32_t centre = a.color[static_cast<size_t>(32 * kSize + 32)];
  EXPECT_GT(channel(centre, 0), 100) << "the quad is lit from the front";
  int worst = 0;
  for (size_t i = 0; i < a.color.size(); ++i)
    for (int k = 0; k < 3; ++k)
      worst = std::max(worst, std::abs(channel(a.color[i], k) - channel(b.color[i], k)));
  EXPECT_LE(worst, 1);
  expectNear3(b.normal[static_cast<size_t>(32 * kSize + 32)], {0, 0, 1}, 1e-4f);
}

// The same quad as a library Object drawn through a mirroring transform, its mesh's winding not
// reversed (as SceneGraph does for glTF nodes): on screen its triangles wind clockwise, so they
// are drawn as back faces, and every shading mode lights them from the viewer's side with the
// vertex normal that faces the viewer, as the unmirrored quad.
TEST(MirroredObject, DoubleSidedShadesTheSideFacingTheViewerInEveryMode) {
  Mesh quad;
  quad.positions = {{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}};
  quad.normals = {{0, 0, 1}, {0, 0, 1}, {0, 0, 1}, {0, 0, 1}};
  quad.indices = {0, 1, 2, 0, 2, 3};
  for (Shading shading : {Shading::kFlat, Shading::kGouraud, Shading::kPhong, Shading::kPbr}) {
    Frame frames[2];
    for (int mirrored = 0; mirrored < 2; ++mirrored) {
      Scene scene;
      Object object;
      object.mesh = std::make_shared<Mesh>(quad);
      object.shading = shading;
      object.cull = CullMode::kNone;
      object.transform.scale = {mirrored ? -1.0f : 1.0f, 1.0f, 1.0f};
      scene.objects.push_back(object);
      scene.lights = {
          Light::directional(normalize(float3{0.0f, -0.5f, -1.0f}), float3(1.0f), 2.0f)};
      scene.ambient = float3(0.0f);
      scene.camera.position = {0, 0, 5};
      RenderOptions o;
      o.width = o.height = kSize;
      o.normals = true;
      CpuRenderer cpu(1);
      cpu.render(scene, o, frames[mirrored]);
    }
    const size_t centre = 32 * kSize + 32;
    EXPECT_GT(channel(frames[0].color[centre], 0), 100) << "shading " << static_cast<int>(shading);
    EXPECT_EQ(frames[1].color[centre], frames[0].color[centre])
        << "shading " << static_cast<int>(shading);
    expectNear3(frames[1].normal[centre], {0, 0, 1}, 1e-5f);
  }
}

}  // namespace
}  // namespace tessera::io
