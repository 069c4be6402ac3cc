// generateTangents (tangents.h): MikkTSpace's rules on meshes small enough to work out by hand
// (angle weighting, a mirrored UV seam, degenerate triangles), a UV sphere against its analytic
// dP/du, and the glTF loader's use of it for a normal-mapped primitive without TANGENT.
//
// No comparison with a file's exported tangents: the one glTF with TANGENT among the installed
// sample models, AnimatedMorphCube, has no TEXCOORD (there is no dP/du to compute) and gives
// (1, 0, 0, 1) at all 24 vertices, along the normal itself on the +-x faces: placeholders, not
// MikkTSpace output (which always lies across the normal).
#include <tessera/scene/tangents.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <tessera/io/model_loader.h>
#include <tessera/scene/primitives.h>

#include "gltf_test_files.h"

namespace tessera {
namespace {

float degreesBetween(float3 a, float3 b) {
  return std::acos(std::clamp(dot(normalize(a), normalize(b)), -1.0f, 1.0f)) * 180.0f / kPi;
}

// Triangle t's corner k's tangent.
float4 cornerTangent(const Mesh& mesh, size_t t, int k) {
  return mesh.tangents[mesh.indices[3 * t + static_cast<size_t>(k)]];
}

// dP/du of a triangle from its positions and UVs.
float3 triangleDpDu(float3 p0, float3 p1, float3 p2, float2 t0, float2 t1, float2 t2) {
  const float3 d1 = p1 - p0, d2 = p2 - p0;
  const float2 s1 = t1 - t0, s2 = t2 - t0;
  return (d1 * s2.y - d2 * s1.y) * (1.0f / (s1.x * s2.y - s1.y * s2.x));
}

// Vertex 0 at the origin is shared by a large triangle (0, 1, 2) and a small one (0, 3, 1), both
// with a right angle there, whose UVs give dP/du 31 degrees apart in direction and of different
// lengths. MikkTSpace weights their unit dP/du by the corners' angles (here equal); weighting by
// area, or summing the unnormalised dP/du as the old generator did, leans elsewhere.
TEST(Tangents, CornersWeighByAngleNotByArea) {
  Mesh mesh;
  mesh.positions = {{0, 0, 0}, {1, 0, 0}, {0, 10, 0}, {0, -1, 0}};
  mesh.normals.assign(4, float3{0, 0, 1});
  mesh.uvs = {{0, 0}, {1, 1}, {0, 10}, {4, 3}};
  mesh.indices = {0, 1, 2, 0, 3, 1};
  const float3 large = triangleDpDu(mesh.positions[0], mesh.positions[1], mesh.positions[2],
                                    mesh.uvs[0], mesh.uvs[1], mesh.uvs[2]);
  const float3 small = triangleDpDu(mesh.positions[0], mesh.positions[3], mesh.positions[1],
                                    mesh.uvs[0], mesh.uvs[3], mesh.uvs[1]);
  const float3 by_angle = normalize(normalize(large) + normalize(small));
  const float3 by_area = normalize(normalize(large) * 5.0f + normalize(small) * 0.5f);
  const float3 summed = normalize(large + small);
  ASSERT_GT(degreesBetween(by_angle, by_area), 10.0f);  // the case tells the weightings apart
  ASSERT_GT(degreesBetween(by_angle, summed), 10.0f);

  const TangentReport report = generateTangents(mesh);
  ASSERT_EQ(mesh.tangents.size(), 4u);
  EXPECT_EQ(report.split_vertices, 0u);
  EXPECT_LT(degreesBetween(mesh.tangents[0].xyz(), by_angle), 0.01f);
  EXPECT_EQ(mesh.tangents[0].w, 1.0f);
  // Vertex 2 belongs to the large triangle alone: its own dP/du.
  EXPECT_LT(degreesBetween(mesh.tangents[2].xyz(), large), 0.01f);
}

// A strip of two quads over x in [-1, 1], y in [0, 1], whose U mirrors at x = 0 (u = |x|): the
// left half's UVs are left-handed. The seam's vertices are shared by both halves.
Mesh mirroredStrip() {
  Mesh mesh;
  for (float y : {0.0f, 1.0f})
    for (float x : {-1.0f, 0.0f, 1.0f}) {
      mesh.positions.push_back({x, y, 0});
      mesh.uvs.push_back({std::fabs(x), y});
    }
  mesh.normals.assign(6, float3{0, 0, 1});
  mesh.colors = {{1, 0, 0, 1}, {0, 1, 0, 1}, {0, 0, 1, 1},
                 {1, 1, 0, 1}, {0, 1, 1, 1}, {1, 0, 1, 1}};
  // Vertices 0 1 2 along y = 0, 3 4 5 along y = 1; counter-clockwise from +z.
  mesh.indices = {0, 1, 4, 0, 4, 3, 1, 2, 5, 1, 5, 4};
  return mesh;
}

TEST(Tangents, MirroredUvSeamSplitsItsVerticesAndKeepsBothSigns) {
  Mesh mesh = mirroredStrip();
  const Mesh before = mesh;
  const TangentReport report = generateTangents(mesh);
  // Vertices 1 and 4 on the seam each get a copy for the other side.
  EXPECT_EQ(report.split_vertices, 2u);
  ASSERT_EQ(mesh.vertexCount(), 8u);
  ASSERT_EQ(mesh.normals.size(), 8u);
  ASSERT_EQ(mesh.uvs.size(), 8u);
  ASSERT_EQ(mesh.colors.size(), 8u);
  ASSERT_EQ(mesh.tangents.size(), 8u);
  for (size_t t = 0; t < mesh.triangleCount(); ++t) {
    const bool left = t < 2;
    for (int k = 0; k < 3; ++k) {
      const float4 tangent = cornerTangent(mesh, t, k);
      // u grows towards -x on the left, +x on the right; v along +y on both: the sign flips.
      EXPECT_LT(degreesBetween(tangent.xyz(), float3{left ? -1.0f : 1.0f, 0, 0}), 0.01f)
          << "triangle " << t << " corner " << k;
      EXPECT_EQ(tangent.w, left ? -1.0f : 1.0f) << "triangle " << t << " corner " << k;
      // The copies carry every attribute of the vertex they were split from.
      const uint32_t v = mesh.indices[3 * t + static_cast<size_t>(k)];
      const uint32_t was = before.indices[3 * t + static_cast<size_t>(k)];
      EXPECT_EQ(mesh.positions[v], before.positions[was]);
      EXPECT_EQ(mesh.normals[v], before.normals[was]);
      EXPECT_EQ(mesh.uvs[v].x, before.uvs[was].x);
      EXPECT_EQ(mesh.uvs[v].y, before.uvs[was].y);
      EXPECT_EQ(mesh.colors[v], before.colors[was]);
    }
  }
}

void expectUnitAcrossNormals(const Mesh& mesh) {
  ASSERT_EQ(mesh.tangents.size(), mesh.vertexCount());
  for (size_t v = 0; v < mesh.vertexCount(); ++v) {
    const float4 t = mesh.tangents[v];
    ASSERT_TRUE(isFinite(t.xyz())) << "vertex " << v;
    EXPECT_NEAR(length(t.xyz()), 1.0f, 1e-5f) << "vertex " << v;
    EXPECT_NEAR(dot(t.xyz(), mesh.normals[v]), 0.0f, 1e-5f) << "vertex " << v;
    EXPECT_TRUE(t.w == 1.0f || t.w == -1.0f) << "vertex " << v;
  }
}

TEST(Tangents, DegenerateUvsAndTrianglesGiveFiniteUnitTangents) {
  // Every UV equal (no gradient anywhere), a triangle of zero area and one with a repeated vertex.
  Mesh mesh;
  mesh.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {2, 0, 0}, {1, 0, 0}};
  mesh.normals = {{0, 0, 1}, {0, 0, 1}, {0, 0, 1}, {1, 0, 0}, {0, 0, 1}};
  mesh.uvs.assign(5, float2{0.5f, 0.5f});
  mesh.indices = {0, 1, 2, 0, 1, 3, 0, 4, 1, 2, 2, 0};
  const TangentReport report = generateTangents(mesh);
  expectUnitAcrossNormals(mesh);
  EXPECT_GT(report.fallback_corners, 0u);

  // Non-finite data around one triangle leaves the others alone.
  Mesh broken = mirroredStrip();
  broken.uvs[0] = {NAN, 0};
  generateTangents(broken);
  expectUnitAcrossNormals(broken);
}

// A triangle with zero UV area beside one with a gradient, across a shared edge, takes its
// neighbour's tangent space (MikkTSpace's "group with any") rather than a fallback; so does its
// corner that no other triangle shares (vertex 3).
TEST(Tangents, TriangleWithoutGradientTakesItsNeighbours) {
  Mesh mesh;
  mesh.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  mesh.normals.assign(4, float3{0, 0, 1});
  // Triangle (0, 1, 2) maps u along (1, 1); (0, 2, 3) has its UVs on one line.
  mesh.uvs = {{0, 0}, {1, -1}, {2, 0}, {3, 0}};
  mesh.indices = {0, 1, 2, 0, 2, 3};
  const TangentReport report = generateTangents(mesh);
  EXPECT_EQ(report.fallback_corners, 0u);
  EXPECT_EQ(report.split_vertices, 0u);
  const float3 expected =
      normalize(triangleDpDu(mesh.positions[0], mesh.positions[1], mesh.positions[2], mesh.uvs[0],
                             mesh.uvs[1], mesh.uvs[2]));
  for (size_t v = 0; v < 4; ++v) {
    EXPECT_LT(degreesBetween(mesh.tangents[v].xyz(), expected), 0.01f) << "vertex " << v;
    EXPECT_EQ(mesh.tangents[v].w, 1.0f) << "vertex " << v;
  }
}

// generateTangents(mesh, ranges) (a glTF mesh whose other primitives gave TANGENT): triangles
// outside the ranges keep their vertices' tangents, and so do the vertices.
TEST(Tangents, RangesLeaveTheOtherVerticesAlone) {
  Mesh mesh = mirroredStrip();
  // A second strip, vertices 6 to 11, with tangents of its own.
  const Mesh strip = mirroredStrip();
  for (size_t v = 0; v < strip.vertexCount(); ++v) {
    mesh.positions.push_back(strip.positions[v] + float3{0, 0, 1});
    mesh.normals.push_back(strip.normals[v]);
    mesh.uvs.push_back(strip.uvs[v]);
    mesh.colors.push_back(strip.colors[v]);
  }
  for (uint32_t i : strip.indices) mesh.indices.push_back(i + 6);
  const float4 given{0, 1, 0, -1};
  mesh.tangents.assign(12, given);
  const VertexRange first_strip{0, 6};
  const TangentReport report = generateTangents(mesh, std::span(&first_strip, 1));
  EXPECT_EQ(report.split_vertices, 2u);
  ASSERT_EQ(mesh.vertexCount(), 14u);
  for (size_t v = 6; v < 12; ++v) EXPECT_EQ(mesh.tangents[v], given) << "vertex " << v;
  for (size_t t = 4; t < 8; ++t)
    for (int k = 0; k < 3; ++k) {
      const uint32_t v = mesh.indices[3 * t + static_cast<size_t>(k)];
      EXPECT_GE(v, 6u);
      EXPECT_LT(v, 12u);
    }
  EXPECT_EQ(cornerTangent(mesh, 0, 0).w, -1.0f);
  EXPECT_EQ(cornerTangent(mesh, 2, 0).w, 1.0f);
}

// On makeUvSphere's sphere (u = phi around +y, v up towards +y) the tangent follows the surface's
// dP/du: along the parallels, the way u grows, with the bitangent up (sign +1).
TEST(Tangents, UvSphereFollowsItsParallels) {
  Mesh sphere = makeUvSphere(48, 24);
  sphere.tangents.clear();
  const size_t vertices = sphere.vertexCount();
  generateTangents(sphere);
  expectUnitAcrossNormals(sphere);
  float worst = 0;
  size_t checked = 0;
  for (size_t v = 0; v < vertices; ++v) {
    const float3 p = sphere.positions[v];
    // The poles' fans have no single parallel. The U seam's vertices (u = 0 and u = 1, not
    // welded) see the triangles of one side only, whose chords lean half a segment off the
    // parallel: MikkTSpace's result there too.
    if (std::fabs(p.y) > 0.95f || sphere.uvs[v].x == 0.0f || sphere.uvs[v].x == 1.0f) continue;
    // Along the parallel: across the y axis and the normal, turned the way u grows.
    const float3 parallel = normalize(cross(float3{0, 1, 0}, p));
    const float3 t = sphere.tangents[v].xyz();
    worst = std::max(worst, degreesBetween(t, parallel));
    EXPECT_EQ(sphere.tangents[v].w, 1.0f) << "vertex " << v;
    ++checked;
  }
  EXPECT_GT(checked, vertices / 2);
  EXPECT_LT(worst, 0.5f);
}

}  // namespace

namespace io {
namespace {

using namespace gltf_test;  // NOLINT(google-build-using-namespace): the tests' own helpers

// The mirrored strip as a glTF primitive with a normal map and no TANGENT: the loader generates
// MikkTSpace tangents and adds the seam's copies to the mesh.
TEST_F(GltfFiles, NormalMappedPrimitiveWithoutTangentsGetsMikkTSpaceOnes) {
  GltfBuilder b;
  const int p = b.positions({{-1, 0, 0}, {0, 0, 0}, {1, 0, 0}, {-1, 1, 0}, {0, 1, 0}, {1, 1, 0}});
  const int n = b.accessor(std::vector<float>{0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1},
                           kFloat, "VEC3", 6);
  // glTF's v runs down the image: v = 1 - y keeps tessera's v along +y.
  const int uv =
      b.accessor(std::vector<float>{1, 1, 0, 1, 1, 1, 1, 0, 0, 0, 1, 0}, kFloat, "VEC2", 6);
  const int i = b.indices({0, 1, 4, 0, 4, 3, 1, 2, 5, 1, 5, 4});
  const int image_view = b.bufferView(pngBytes(1, 1, {0xffff8080}));
  const std::vector<uint8_t> glb =
      b.glb(kOneNodeScene + "," +
            oneMesh(p, ",\"NORMAL\":" + std::to_string(n) + ",\"TEXCOORD_0\":" + std::to_string(uv),
                    ",\"indices\":" + std::to_string(i) + ",\"material\":0") +
            ",\"materials\":[{\"normalTexture\":{\"index\":0}}],\"textures\":[{\"source\":0}],"
            "\"images\":[{\"bufferView\":" +
            std::to_string(image_view) + ",\"mimeType\":\"image/png\"}]");
  Expected<Model> model = loadGltf(write(at("strip.glb"), glb));
  ASSERT_TRUE(model) << model.error().message;
  ASSERT_EQ(model->graph.meshes.size(), 1u);
  const Mesh& mesh = *model->graph.meshes[0].mesh;
  ASSERT_EQ(mesh.vertexCount(), 8u);  // the seam's two vertices split
  ASSERT_EQ(mesh.tangents.size(), 8u);
  for (size_t t = 0; t < mesh.triangleCount(); ++t)
    for (int k = 0; k < 3; ++k) {
      const float4 tangent = cornerTangent(mesh, t, k);
      const bool left = t < 2;
      EXPECT_LT(degreesBetween(tangent.xyz(), float3{left ? -1.0f : 1.0f, 0, 0}), 0.01f);
      EXPECT_EQ(tangent.w, left ? -1.0f : 1.0f);
    }
}

}  // namespace
}  // namespace io
}  // namespace tessera
