#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>

#include <tessera/math/math.h>

using namespace tessera;

namespace {

void expectNear(float3 a, float3 b, float eps = 1e-5f) {
  EXPECT_NEAR(a.x, b.x, eps);
  EXPECT_NEAR(a.y, b.y, eps);
  EXPECT_NEAR(a.z, b.z, eps);
}

float3 project(const float4x4& m, float3 p) {
  float4 c = m * float4{p, 1.0f};
  return c.xyz() * (1.0f / c.w);
}

}  // namespace

TEST(Math, CrossFollowsRightHandRule) {
  expectNear(cross({1, 0, 0}, {0, 1, 0}), {0, 0, 1});
  expectNear(cross({0, 1, 0}, {0, 0, 1}), {1, 0, 0});
}

TEST(Math, MatrixProductComposesRightToLeft) {
  // Scale then translate: T * S applied to (1, 0, 0) is (2, 0, 0) + (0, 5, 0).
  float4x4 m = translation({0, 5, 0}) * scaling({2, 2, 2});
  expectNear((m * float4{1, 0, 0, 1}).xyz(), {2, 5, 0});
}

// The 4x4 product runs four lanes at a time; it must give the bits of the column formula (the
// image's hash depends on them), here over matrices with no zero, huge and tiny entries.
TEST(Math, MatrixProductHasTheBitsOfTheColumnFormula) {
  float4x4 a, b;
  uint32_t seed = 12345;
  auto next = [&] {
    seed = seed * 1664525u + 1013904223u;
    const float unit = static_cast<float>(seed >> 8) / 16777216.0f - 0.5f;
    return unit * std::ldexp(1.0f, static_cast<int>(seed % 40) - 20);
  };
  for (int round = 0; round < 50; ++round) {
    for (int c = 0; c < 4; ++c)
      for (int r = 0; r < 4; ++r) a(r, c) = next(), b(r, c) = next();
    const float4x4 product = a * b;
    for (int c = 0; c < 4; ++c) {
      const float4 v = b.col[c];
      for (int r = 0; r < 4; ++r) {
        const float expected = a(r, 0) * v.x + a(r, 1) * v.y + a(r, 2) * v.z + a(r, 3) * v.w;
        EXPECT_EQ(std::bit_cast<uint32_t>(product(r, c)), std::bit_cast<uint32_t>(expected))
            << "row " << r << ", column " << c;
      }
    }
  }
}

TEST(Math, InverseUndoesAGeneralTransform) {
  float4x4 m =
      translation({1, -2, 3}) * toMatrix4(fromEuler({0.3f, -1.1f, 2.0f})) * scaling({2, 0.5f, 3});
  float4x4 identity = m * inverse(m);
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) EXPECT_NEAR(identity(r, c), r == c ? 1.0f : 0.0f, 1e-5f);
  float3x3 m3 = upper3x3(m);
  float3x3 i3 = m3 * inverse(m3);
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(i3(r, c), r == c ? 1.0f : 0.0f, 1e-5f);
}

TEST(Math, NormalMatrixKeepsNormalsPerpendicularUnderNonUniformScale) {
  // A plane through the origin containing (1, 1, 0) and (0, 0, 1): normal (1, -1, 0).
  float4x4 m = scaling({4, 1, 1});
  float3 tangent = (m * float4{1, 1, 0, 0}).xyz();
  float3 n = normalMatrix(m) * float3{1, -1, 0};
  EXPECT_NEAR(dot(tangent, n), 0.0f, 1e-5f);
  // Transforming the normal like a position would break that.
  EXPECT_GT(std::fabs(dot(tangent, (m * float4{1, -1, 0, 0}).xyz())), 1.0f);
}

TEST(Math, EulerComposesZTimesYTimesX) {
  float3 angles{0.4f, -0.7f, 1.2f};
  float3x3 expected = toMatrix3(quat::fromAxisAngle({0, 0, 1}, angles.z)) *
                      toMatrix3(quat::fromAxisAngle({0, 1, 0}, angles.y)) *
                      toMatrix3(quat::fromAxisAngle({1, 0, 0}, angles.x));
  float3x3 got = toMatrix3(fromEuler(angles));
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(got(r, c), expected(r, c), 1e-5f);
  // A quarter turn about Z takes +X to +Y (counter-clockwise, right-handed).
  expectNear(rotate(quat::fromAxisAngle({0, 0, 1}, kPi / 2), {1, 0, 0}), {0, 1, 0});
}

TEST(Math, LookAtPutsTargetOnMinusZ) {
  float4x4 v = lookAt({3, 4, 5}, {1, 1, 1}, {0, 1, 0});
  float3 target = (v * float4{1, 1, 1, 1}).xyz();
  EXPECT_NEAR(target.x, 0.0f, 1e-5f);
  EXPECT_NEAR(target.y, 0.0f, 1e-5f);
  EXPECT_NEAR(target.z, -length(float3{2, 3, 4}), 1e-5f);
  // The up vector stays up: a point above the target is above in view space.
  EXPECT_GT((v * float4{1, 2, 1, 1}).y, 0.0f);
}

TEST(Math, LookAtAlongUpVectorStaysFinite) {
  float4x4 v = lookAt({0, 10, 0}, {0, 0, 0}, {0, 1, 0});
  for (int c = 0; c < 4; ++c) EXPECT_TRUE(std::isfinite(v.col[c].x + v.col[c].y + v.col[c].z));
  EXPECT_NEAR((v * float4{0, 0, 0, 1}).z, -10.0f, 1e-4f);
  EXPECT_NEAR(std::fabs(determinant(upper3x3(v))), 1.0f, 1e-5f);
}

TEST(Math, PerspectiveMapsNearAndFarToMinusOneAndOne) {
  float4x4 p = perspective(radians(60.0f), 1.5f, 0.5f, 50.0f);
  EXPECT_NEAR(project(p, {0, 0, -0.5f}).z, -1.0f, 1e-5f);
  EXPECT_NEAR(project(p, {0, 0, -50.0f}).z, 1.0f, 1e-4f);
  // The top of the field of view at distance d is d * tan(30 deg): NDC y = 1.
  EXPECT_NEAR(project(p, {0, 2.0f * std::tan(radians(30.0f)), -2.0f}).y, 1.0f, 1e-5f);
  EXPECT_NEAR(project(p, {1.5f * 2.0f * std::tan(radians(30.0f)), 0, -2.0f}).x, 1.0f, 1e-5f);
}

TEST(Math, ZeroToOnePerspectiveGivesTheSameWindowDepth) {
  float4x4 gl = perspective(radians(50.0f), 1.0f, 0.1f, 10.0f);
  float4x4 zo = perspectiveZeroToOne(radians(50.0f), 1.0f, 0.1f, 10.0f);
  EXPECT_NEAR(project(zo, {0, 0, -0.1f}).z, 0.0f, 1e-5f);
  EXPECT_NEAR(project(zo, {0, 0, -10.0f}).z, 1.0f, 1e-5f);
  for (float z : {-0.2f, -1.0f, -3.0f, -9.0f})
    EXPECT_NEAR(project(gl, {0, 0, z}).z * 0.5f + 0.5f, project(zo, {0, 0, z}).z, 1e-5f);
}

TEST(Math, ViewportPutsPixelZeroTopLeft) {
  Viewport vp{640, 480};
  expectNear(vp.toWindow({-1, 1, -1}), {0, 0, 0});
  expectNear(vp.toWindow({1, -1, 1}), {640, 480, 1});
  float3 m = (vp.matrix() * float4{0.5f, 0.5f, 0.0f, 1.0f}).xyz();
  expectNear(m, vp.toWindow({0.5f, 0.5f, 0.0f}));
}
