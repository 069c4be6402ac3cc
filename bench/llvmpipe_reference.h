// The reference `tessera bench --vs llvmpipe` measures against: the same scene drawn through
// Mesa's OpenGL in an off-screen OSMesa context, which renders with llvmpipe. Same triangles,
// camera matrices, lights and lighting model (GLSL 1.20: flat, Gouraud, per-pixel Phong, unlit;
// GLSL 4.50: glTF's PBR per pixel), the same tone curve and exposure, the same back-face culling
// and depth test, from buffers uploaded once; every frame ends with glFinish (single-sampled) or
// with the resolved image read back (multisampled, setSamples). Built only with TESSERA_OSMESA;
// otherwise create() says so.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <tessera/base/expected.h>
#include <tessera/scene/scene.h>

namespace tessera::bench {

// Whether this build has the OSMesa reference.
bool llvmpipeReferenceBuilt();

class LlvmpipeReference {
 public:
  // Creates the OSMesa context. llvmpipe takes its thread count from the environment variable
  // LP_NUM_THREADS when its screen is created, once per process: the first create() sets it to
  // `workers` (0 = one per hardware thread), and a later create() with another count is an error.
  static Expected<std::unique_ptr<LlvmpipeReference>> create(int workers);
  ~LlvmpipeReference();
  LlvmpipeReference(const LlvmpipeReference&) = delete;
  LlvmpipeReference& operator=(const LlvmpipeReference&) = delete;

  const std::string& renderer() const;  // GL_RENDERER, e.g. "llvmpipe (LLVM 15.0.6, 256 bits)"
  const std::string& version() const;   // GL_VERSION, which names the Mesa version
  bool isLlvmpipe() const;              // the renderer string says llvmpipe
  int threads() const;                  // the LP_NUM_THREADS it was created with

  // Uploads the scene's meshes and textures into buffers and compiles its shaders (for its lights
  // and its tone curve: render() takes the scene with the same); replaces the previous scene.
  // Errors: more lights than the shaders take, a PBR map it does not draw, a GL failure.
  Expected<void> setScene(const Scene& scene);
  // Sizes the colour and depth buffers.
  Expected<void> setResolution(int width, int height);
  // Samples per pixel: 1 (the default), 2, 4 or 8 (isSampleCount). Above 1 every frame is drawn
  // into a multisampled framebuffer object of exactly that many samples and resolved in linear
  // light (llvmpipe_multisample.h). An error, naming the counts the context has, when it cannot
  // give exactly `samples` (llvmpipe has 4 only); the count then stays as it was.
  Expected<void> setSamples(int samples);
  int samples() const;
  // Draws the scene given to setScene (the same objects; their transforms, the camera, the
  // lights and the background are read now) and waits for it to finish; multisampled, that
  // includes the resolve and the read-back that readColor() then returns.
  void render(const Scene& scene);
  // The last frame as RGBA8 sRGB, R in the low byte, row 0 at the top (like Frame::color).
  void readColor(std::vector<uint32_t>& rgba) const;

  static constexpr int kMaxLights = 8;

 private:
  LlvmpipeReference();
  struct State;
  std::unique_ptr<State> state_;
};

}  // namespace tessera::bench
