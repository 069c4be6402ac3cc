// Keyframe animation (scene/animation.h): each interpolation against the formula of glTF's
// appendix C computed here, and a node's transform at time t after Animation::apply.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include <tessera/scene/animation.h>
#include <tessera/scene/graph.h>

namespace tessera {
namespace {

constexpr float kTolerance = 1e-5f;

void expectNear(float4 got, float4 want, const char* what) {
  EXPECT_NEAR(got.x, want.x, kTolerance) << what;
  EXPECT_NEAR(got.y, want.y, kTolerance) << what;
  EXPECT_NEAR(got.z, want.z, kTolerance) << what;
  EXPECT_NEAR(got.w, want.w, kTolerance) << what;
}

AnimationSampler translationSampler(Interpolation interpolation) {
  AnimationSampler s;
  s.interpolation = interpolation;
  s.times = {1.0f, 2.0f, 4.0f};
  s.values = {{0, 0, 0, 0}, {2, -4, 6, 0}, {3, 0, 1, 0}};
  return s;
}

TEST(Animation, StepHoldsEachKeyframeUntilTheNext) {
  const AnimationSampler s = translationSampler(Interpolation::kStep);
  expectNear(sampleAnimation(s, 0.5f, false), {0, 0, 0, 0}, "before the first key");
  expectNear(sampleAnimation(s, 1.0f, false), {0, 0, 0, 0}, "at the first key");
  expectNear(sampleAnimation(s, 1.99f, false), {0, 0, 0, 0}, "just before the second");
  expectNear(sampleAnimation(s, 2.0f, false), {2, -4, 6, 0}, "at the second");
  expectNear(sampleAnimation(s, 3.5f, false), {2, -4, 6, 0}, "between second and third");
  expectNear(sampleAnimation(s, 9.0f, false), {3, 0, 1, 0}, "after the last");
}

TEST(Animation, LinearBlendsBetweenTheTwoKeyframesAround) {
  const AnimationSampler s = translationSampler(Interpolation::kLinear);
  expectNear(sampleAnimation(s, 1.25f, false), {0.5f, -1.0f, 1.5f, 0}, "a quarter of the way");
  // Between t = 2 and t = 4, t = 3.5 is three quarters of the way.
  const float a = 0.75f;
  expectNear(sampleAnimation(s, 3.5f, false),
             {2 + (3 - 2) * a, -4 + (0 + 4) * a, 6 + (1 - 6) * a, 0}, "three quarters");
  expectNear(sampleAnimation(s, -3.0f, false), {0, 0, 0, 0}, "clamped before");
  expectNear(sampleAnimation(s, 40.0f, false), {3, 0, 1, 0}, "clamped after");
}

TEST(Animation, CubicSplineIsTheHermiteCurveOfTheFilesTangents) {
  AnimationSampler s;
  s.interpolation = Interpolation::kCubicSpline;
  s.times = {0.0f, 2.0f};
  // Per keyframe: in-tangent, value, out-tangent.
  const float4 a0{9, 9, 9, 0}, v0{1, 0, -1, 0}, b0{0.5f, 2, 0, 0};
  const float4 a1{-1, 1, 3, 0}, v1{3, 1, 2, 0}, b1{7, 7, 7, 0};
  s.values = {a0, v0, b0, a1, v1, b1};
  const float t = 0.5f, td = 2.0f, u = t / td;
  const float h00 = 2 * u * u * u - 3 * u * u + 1, h10 = td * (u * u * u - 2 * u * u + u);
  const float h01 = -2 * u * u * u + 3 * u * u, h11 = td * (u * u * u - u * u);
  auto comp = [&](float v0c, float b0c, float v1c, float a1c) {
    return h00 * v0c + h10 * b0c + h01 * v1c + h11 * a1c;
  };
  expectNear(sampleAnimation(s, t, false),
             {comp(v0.x, b0.x, v1.x, a1.x), comp(v0.y, b0.y, v1.y, a1.y),
              comp(v0.z, b0.z, v1.z, a1.z), 0},
             "Hermite at a quarter");
  expectNear(sampleAnimation(s, 0.0f, false), v0, "at the first key: its value, not a tangent");
  expectNear(sampleAnimation(s, 2.0f, false), v1, "at the last key");
}

TEST(Animation, RotationSlerpsAlongTheShorterArc) {
  AnimationSampler s;
  s.times = {0.0f, 1.0f};
  const quat from = quat::fromAxisAngle({0, 1, 0}, 0.0f);
  const quat to = quat::fromAxisAngle({0, 1, 0}, 1.5f);
  s.values = {{from.x, from.y, from.z, from.w}, {to.x, to.y, to.z, to.w}};
  const quat third = quat::fromAxisAngle({0, 1, 0}, 0.5f);
  expectNear(sampleAnimation(s, 1.0f / 3.0f, true), {third.x, third.y, third.z, third.w},
             "a third of 1.5 rad about Y");
  // The same end rotation written as -q: still the short way round, not 2 pi - 1.5.
  s.values[1] = {-to.x, -to.y, -to.z, -to.w};
  const float4 q = sampleAnimation(s, 1.0f / 3.0f, true);
  const float sign = q.w < 0 ? -1.0f : 1.0f;
  expectNear({q.x * sign, q.y * sign, q.z * sign, q.w * sign}, {third.x, third.y, third.z, third.w},
             "-q is the same rotation");
}

TEST(Animation, CubicRotationIsNormalized) {
  AnimationSampler s;
  s.interpolation = Interpolation::kCubicSpline;
  s.times = {0.0f, 1.0f};
  const float r = std::sqrt(0.5f);
  s.values = {{0, 0, 0, 0}, {0, 0, 0, 1}, {0, 0, 0, 0}, {0, 0, 0, 0}, {0, r, 0, r}, {0, 0, 0, 0}};
  const float4 q = sampleAnimation(s, 0.5f, true);
  EXPECT_NEAR(q.x * q.x + q.y * q.y + q.z * q.z + q.w * q.w, 1.0f, 1e-5f);
  EXPECT_GT(q.y, 0.0f);
}

// An animated cube: node 1 (child of node 0) spins about Y and moves along X; at t its world
// matrix is the parent's times the keyframes' interpolation computed here.
TEST(Animation, ApplySetsTheNodesTransformAtTimeT) {
  SceneGraph graph;
  graph.nodes.resize(2);
  graph.nodes[0].local.translation = {0, 10, 0};
  graph.nodes[1].parent = 0;
  Animation animation;
  animation.name = "spin";
  AnimationSampler move;
  move.times = {0.0f, 2.0f};
  move.values = {{0, 0, 0, 0}, {4, 0, 0, 0}};
  AnimationSampler spin;
  spin.times = {0.0f, 2.0f};
  const quat end = quat::fromAxisAngle({0, 1, 0}, 1.0f);
  spin.values = {{0, 0, 0, 1}, {end.x, end.y, end.z, end.w}};
  AnimationSampler stepped;
  stepped.interpolation = Interpolation::kStep;
  stepped.times = {0.0f, 1.0f};
  stepped.values = {{2, 2, 2, 0}, {1, 1, 1, 0}};
  animation.samplers = {move, spin, stepped};
  animation.channels = {{1, AnimatedProperty::kTranslation, 0},
                        {1, AnimatedProperty::kRotation, 1},
                        {0, AnimatedProperty::kScale, 2}};
  ASSERT_TRUE(validateAnimation(animation, graph.nodes.size()).ok());
  EXPECT_FLOAT_EQ(animation.startTime(), 0.0f);
  EXPECT_FLOAT_EQ(animation.endTime(), 2.0f);

  animation.apply(0.5f, graph);
  graph.updateWorld();
  // Node 0's scale is stepped: 2 until t = 1, then 1.
  EXPECT_FLOAT_EQ(graph.nodes[0].local.scale.x, 2.0f);
  EXPECT_NEAR(graph.world[1].col[3].y, 10.0f, 1e-5f);
  EXPECT_NEAR(graph.world[1].col[3].x, 2.0f * 1.0f, 1e-5f);  // translation 1 at t = 0.5, scaled
  animation.apply(1.5f, graph);
  graph.updateWorld();
  const float4x4 expected_local =
      translation(float3{3, 0, 0}) * toMatrix4(quat::fromAxisAngle({0, 1, 0}, 0.75f));
  const float4x4 expected = translation(float3{0, 10, 0}) * expected_local;
  for (int c = 0; c < 4; ++c) {
    for (int r = 0; r < 4; ++r) {
      EXPECT_NEAR(graph.world[1].col[c][r], expected.col[c][r], 1e-5f) << c << "," << r;
    }
  }
}

// A triangle at x = 1 turned half way round about Y: its rest bounds end at x = 1, the clip's
// reach x = -1 too (the near and far planes of an animated model come from these).
TEST(Animation, ClipBoundsCoverEveryPose) {
  SceneGraph graph;
  GraphMesh mesh;
  auto triangle = std::make_shared<Mesh>();
  triangle->positions = {{1, 0, 0}, {1, 0.1f, 0}, {1, 0, 0.1f}};
  triangle->indices = {0, 1, 2};
  mesh.mesh = triangle;
  graph.meshes.push_back(mesh);
  graph.nodes.resize(1);
  graph.nodes[0].mesh = 0;
  Animation clip;
  AnimationSampler turn;
  turn.times = {0.0f, 1.0f};
  const quat half = quat::fromAxisAngle({0, 1, 0}, 3.14159265f);
  turn.values = {{0, 0, 0, 1}, {half.x, half.y, half.z, half.w}};
  clip.samplers = {turn};
  clip.channels = {{0, AnimatedProperty::kRotation, 0}};
  graph.updateWorld();
  EXPECT_NEAR(graph.bounds().min.x, 1.0f, 1e-5f);
  const Bounds b = clipBounds(clip, graph);
  EXPECT_NEAR(b.min.x, -1.005f, 1e-2f);  // the far corner, radius sqrt(1 + 0.01)
  EXPECT_NEAR(b.max.x, 1.0f, 1e-3f);
  // A quarter turn takes x = 1 to z = -1 or, the way this half turn goes, z = +1.
  EXPECT_GT(b.max.z - b.min.z, 0.9f);
  EXPECT_NEAR(graph.world[0].col[0].x, 1.0f, 1e-6f);  // left at the clip's start
}

TEST(Animation, ValidationNamesTheSamplerOrChannel) {
  Animation animation;
  animation.name = "walk";
  AnimationSampler bad;
  bad.times = {0.0f, 1.0f, 1.0f};
  bad.values = {{0, 0, 0, 0}, {1, 0, 0, 0}, {2, 0, 0, 0}};
  animation.samplers = {bad};
  animation.channels = {{0, AnimatedProperty::kTranslation, 0}};
  Expected<void> result = validateAnimation(animation, 1);
  ASSERT_FALSE(result.ok());
  EXPECT_NE(result.error().message.find("animation 'walk' sampler 0"), std::string::npos);
  EXPECT_NE(result.error().message.find("must increase"), std::string::npos);

  animation.samplers[0].times = {0.0f, 1.0f, 2.0f};
  animation.samplers[0].interpolation = Interpolation::kCubicSpline;  // needs 9 values
  result = validateAnimation(animation, 1);
  ASSERT_FALSE(result.ok());
  EXPECT_NE(result.error().message.find("3 per keyframe"), std::string::npos);

  animation.samplers[0].interpolation = Interpolation::kLinear;
  animation.channels[0].node = 5;
  result = validateAnimation(animation, 1);
  ASSERT_FALSE(result.ok());
  EXPECT_NE(result.error().message.find("channel 0 names node 5 of 1"), std::string::npos);
}

}  // namespace
}  // namespace tessera
