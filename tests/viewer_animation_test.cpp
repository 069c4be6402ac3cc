// The viewer's animation playback and start camera without a window: the space bar's player
// (animation_player.h) against a clip built here, and the orbit camera started from a file's
// camera (OrbitCamera::frameCamera).
#include <gtest/gtest.h>

#include <chrono>
#include <memory>

#include <tessera/scene/graph.h>
#include <tessera/scene/primitives.h>
#include <tessera/viewer/animation_player.h>
#include <tessera/viewer/orbit_camera.h>

using namespace tessera;
using namespace tessera::viewer;

namespace {

using Clock = AnimationPlayer::Clock;

Clock::time_point at(double seconds) {
  return Clock::time_point() +
         std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(seconds));
}

// One cube node moved along +X by x = t over the clip "slide" (keys at 1 s and 3 s: x 0 to 2),
// as a loaded scene: the graph's instance is object 0.
LoadedScene slidingCube() {
  LoadedScene loaded;
  SceneGraph& graph = loaded.graph;
  GraphMesh mesh;
  mesh.mesh = std::make_shared<const Mesh>(makeCube());
  graph.meshes.push_back(mesh);
  GraphNode node;
  node.mesh = 0;
  graph.nodes.push_back(node);
  Animation clip;
  clip.name = "slide";
  AnimationSampler sampler;
  sampler.times = {1.0f, 3.0f};
  sampler.values = {{0, 0, 0, 0}, {2, 0, 0, 0}};
  clip.samplers.push_back(sampler);
  clip.channels.push_back({0, AnimatedProperty::kTranslation, 0});
  graph.animations.push_back(clip);
  graph.updateWorld();
  graph.prepareMeshes();
  instantiate(graph, Object{}, loaded.scene);
  return loaded;
}

float objectX(const Scene& scene) {
  return scene.objects.at(0).transform.matrix().col[3].x;
}

TEST(AnimationPlayer, PlaysByWallClockTimeAndLoopsOverTheClip) {
  LoadedScene loaded = slidingCube();
  prepareClip(loaded, 0);
  AnimationPlayer player;
  player.reset(std::move(loaded.graph), loaded.clip);
  ASSERT_TRUE(player.hasClip());
  EXPECT_FALSE(player.playing());  // paused at the start until space
  EXPECT_FALSE(player.update(at(10.0), loaded.scene));
  ASSERT_TRUE(player.togglePlaying(at(10.0)));
  EXPECT_TRUE(player.playing());
  ASSERT_TRUE(player.update(at(10.5), loaded.scene));
  EXPECT_NEAR(objectX(loaded.scene), 0.5f, 1e-5f);  // key time 1.5: x = 0.5
  ASSERT_TRUE(player.update(at(11.5), loaded.scene));
  EXPECT_NEAR(player.time(), 1.5, 1e-6);
  EXPECT_NEAR(objectX(loaded.scene), 1.5f, 1e-5f);
  // 2.75 s into a 2 s clip: 0.75 s into its second loop.
  ASSERT_TRUE(player.update(at(12.75), loaded.scene));
  EXPECT_NEAR(player.time(), 0.75, 1e-6);
  EXPECT_NEAR(objectX(loaded.scene), 0.75f, 1e-5f);
}

TEST(AnimationPlayer, PausedHoldsThePoseAndThePauseDoesNotCount) {
  LoadedScene loaded = slidingCube();
  prepareClip(loaded, 0);
  AnimationPlayer player;
  player.reset(std::move(loaded.graph), loaded.clip);
  player.togglePlaying(at(0.0));
  player.update(at(0.5), loaded.scene);
  ASSERT_TRUE(player.togglePlaying(at(0.6)));  // pause on the pose drawn: 0.5 s
  EXPECT_FALSE(player.playing());
  EXPECT_FALSE(player.update(at(5.0), loaded.scene));
  EXPECT_NEAR(objectX(loaded.scene), 0.5f, 1e-5f);
  EXPECT_NE(player.describe().find("paused"), std::string::npos) << player.describe();
  EXPECT_NE(player.describe().find("'slide' 0.50 / 2.00 s"), std::string::npos)
      << player.describe();
  EXPECT_EQ(player.state(), "animation paused at 0.500 s");
  player.togglePlaying(at(20.0));
  ASSERT_TRUE(player.update(at(20.25), loaded.scene));
  EXPECT_NEAR(objectX(loaded.scene), 0.75f, 1e-5f);
  EXPECT_NE(player.describe().find("playing"), std::string::npos);
}

TEST(AnimationPlayer, WithoutAClipSpaceChangesNothing) {
  LoadedScene loaded = slidingCube();
  loaded.graph.animations.clear();
  prepareClip(loaded, 0);  // past the end: none
  EXPECT_EQ(loaded.clip, -1);
  AnimationPlayer player;
  player.reset(std::move(loaded.graph), loaded.clip);
  EXPECT_FALSE(player.hasClip());
  EXPECT_FALSE(player.togglePlaying(at(0.0)));
  EXPECT_FALSE(player.playing());
  EXPECT_FALSE(player.update(at(1.0), loaded.scene));
  EXPECT_EQ(player.describe(), "");
}

TEST(AnimationPlayer, PrepareClipPosesTheStartAndFramesTheWholeMotion) {
  LoadedScene loaded = slidingCube();
  // Moved somewhere else by hand: prepareClip poses the clip's start (x = 0) again.
  loaded.graph.nodes[0].local.translation = {7, 0, 0};
  loaded.graph.updateWorld();
  updateInstances(loaded.graph, 0, loaded.scene);
  prepareClip(loaded, 0);
  EXPECT_EQ(loaded.clip, 0);
  EXPECT_NEAR(objectX(loaded.scene), 0.0f, 1e-6f);
  // The unit cube (-0.5..0.5) slides 2 along +X: the bounds reach from -0.5 to 2.5.
  EXPECT_NEAR(loaded.bounds.min.x, -0.5f, 1e-5f);
  EXPECT_NEAR(loaded.bounds.max.x, 2.5f, 1e-5f);
  EXPECT_NEAR(loaded.bounds.max.y, 0.5f, 1e-5f);
}

Bounds unitBounds() {
  Bounds b;
  b.add({-1, -1, -1});
  b.add({1, 1, 1});
  return b;
}

TEST(OrbitCamera, StartsFromAGivenCameraExactlyAndEnterReturnsToIt) {
  Camera file;
  file.position = {0, 0, 6};
  file.target = {0, 0, 5};  // one unit ahead, as a glTF camera's
  file.up = {1, 0, 0};      // rolled: the orbit's own up differs
  file.fov_y_degrees = 20.0f;
  file.near_z = 0.5f, file.far_z = 40.0f;
  OrbitCamera orbit;
  orbit.frameCamera(file, unitBounds());
  const Camera start = orbit.camera();
  EXPECT_EQ(start.position.z, 6.0f);
  EXPECT_EQ(start.up.x, 1.0f);
  EXPECT_EQ(start.fov_y_degrees, 20.0f);
  EXPECT_EQ(start.far_z, 40.0f);
  // It turns about the model's centre, at the camera's distance, with its field of view.
  EXPECT_NEAR(orbit.distance(), 6.0f, 1e-5f);
  orbit.orbit(0.25f, 0.0f);
  const Camera turned = orbit.camera();
  EXPECT_GT(std::abs(turned.position.x), 1.0f);
  EXPECT_NEAR(length(turned.position), 6.0f, 1e-4f);
  EXPECT_EQ(turned.fov_y_degrees, 20.0f);
  orbit.reset();
  const Camera back = orbit.camera();
  EXPECT_EQ(back.position.x, file.position.x);
  EXPECT_EQ(back.up.x, 1.0f);
  EXPECT_EQ(back.near_z, 0.5f);
  // A later frame() forgets the start camera.
  orbit.frame(unitBounds(), {0, 0, 1}, 50.0f, 1.0f);
  orbit.reset();
  EXPECT_NE(orbit.camera().fov_y_degrees, 20.0f);
}

TEST(OrbitCamera, AnOrthographicStartStaysOrthographicAndZoomScalesIt) {
  Camera file;
  file.position = {0, 0, 4};
  file.target = {0, 0, 0};
  file.orthographic = true;
  file.ortho_half_height = 1.5f;
  OrbitCamera orbit;
  orbit.frameCamera(file, unitBounds());
  EXPECT_TRUE(orbit.camera().orthographic);
  orbit.orbit(0.1f, 0.1f);
  Camera moved = orbit.camera();
  EXPECT_TRUE(moved.orthographic);
  EXPECT_NEAR(moved.ortho_half_height, 1.5f, 1e-5f);
  EXPECT_GE(moved.near_z, 0.0f);
  orbit.zoom(1.0f);  // 10% closer: 10% less high
  EXPECT_NEAR(orbit.camera().ortho_half_height, 1.35f, 1e-5f);
  // The nonlinear modes draw their own rays: no orthographic camera there.
  orbit.setProjection(Projection::kFisheye, 180.0f);
  EXPECT_FALSE(orbit.camera().orthographic);
}

}  // namespace
