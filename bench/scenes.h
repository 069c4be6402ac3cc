// The scenes `tessera bench` and the micro-benchmarks time: built-in ones by name, or any model
// file. A BenchScene holds the objects and says how the model turns from frame to frame; the
// caller places the camera and lights (apps/tessera/view_setup.h frames a model the way
// `tessera render` does) unless the scene brings its own view.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include <tessera/base/expected.h>
#include <tessera/io/model_loader.h>
#include <tessera/scene/scene.h>

namespace tessera::bench {

// The Stanford bunny as Debian's glmark2-data installs it.
inline constexpr const char* kBunnyPath = "/usr/share/glmark2/models/bunny.obj";
inline constexpr const char* kBunnyPackage = "glmark2-data";

// Triangle counts of the built-in scenes (tests hold the scenes to them).
inline constexpr size_t kCubeTriangles = 12;
inline constexpr size_t kBunnyTriangles = 69'666;
inline constexpr size_t kDenseTriangles = 1'000'000;
inline constexpr size_t kFillLayers = 10;
inline constexpr size_t kFillTriangles = 2 * kFillLayers;
inline constexpr size_t kTexturedTriangles = 16'128;
inline constexpr size_t kCloudPoints = 10'000'000;

// How far the model turns between two frames, in degrees.
inline constexpr float kTurnDegreesPerFrame = 2.0f;

struct BenchScene {
  std::string name;
  Scene scene;
  Bounds bounds;              // world bounds of the model at rest (what a framing camera fits)
  float3 spin_axis{0, 1, 0};  // every object turns about this axis through `pivot`
  float3 pivot;
  // The scene's camera and lights are part of it (the fill scene: its layers must cover the
  // screen); otherwise they are the caller's to set.
  bool fixed_view = false;
  // Whether poseForFrame turns the objects. The many-instance scene holds still: turned about the
  // origin, its grid left the view within 40 frames, so a run's timed frames went from 1% of it in
  // view to none.
  bool spins = true;
  std::vector<std::string> warnings;  // from the model loader
};

// 10,000 instances of a 1,000-triangle sphere, about 1% of them in view (the frustum culling
// scene), or (`flattened`) the same triangles as one mesh, for the comparison in docs/perf.md.
BenchScene makeInstancesScene(Shading shading, bool flattened);

// A terrain of kCloudPoints coloured points (no triangles): a jittered 4000 x 2500 grid over
// 4 x 2.5 units, heights from a few waves and a hash, coloured by height, under its own camera
// and light (the point pass's scene in docs/perf.md). The same points every time.
BenchScene makePointCloudScene();

// The names of the built-in scenes, in the order a full run takes them.
std::vector<std::string> builtinSceneNames();
bool isBuiltinScene(const std::string& name);
// Scenes made by name but left out of a full run: instances-flat (10 million triangles), points
// (makePointCloudScene, which llvmpipe's reference does not draw).
std::vector<std::string> extraSceneNames();

// A built-in scene:
//   cube      the unit cube (12 triangles)
//   bunny     the Stanford bunny (69,666 triangles), read from kBunnyPath
//   dense     a UV sphere of 1,000,000 small triangles
//   fill      ten screen-covering quads at different depths drawn back to front (overdraw 10)
//   textured  a UV sphere (16,128 triangles) with a procedural checker texture
// and the extraSceneNames().
// Every object gets `shading` and back faces culled. An unknown name or a missing bunny is an
// error naming what to do.
Expected<BenchScene> makeBuiltinScene(const std::string& name, Shading shading);

// A model file through io::loadModel, as one object with `shading` and back faces culled.
Expected<BenchScene> loadModelScene(const std::filesystem::path& path, Shading shading,
                                    const io::LoadBudget& budget = {});

// Poses the scene for frame `frame`: every object turned by frame * kTurnDegreesPerFrame about
// the spin axis through the pivot (nothing for a scene that does not spin).
void poseForFrame(BenchScene& bench_scene, int frame);

// A square checker texture of `cells` x `cells` cells, `size` texels a side (sRGB).
Texture makeCheckerTexture(int size, int cells);

}  // namespace tessera::bench
