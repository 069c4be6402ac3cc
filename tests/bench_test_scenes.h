// What the benchmark's tests share: a built-in scene by name, the cube demo's view, and render
// options for colour and triangle ids.
#pragma once

#include <string>

#include <tessera/render/options.h>

#include "bench/scenes.h"

namespace tessera::test {

inline Expected<bench::BenchScene> scene(const std::string& name,
                                         Shading shading = Shading::kGouraud) {
  return bench::makeBuiltinScene(name, shading);
}

// The cube demo's view: the caller of a scene places camera and lights.
inline void lookAtCube(Scene& s) {
  s.camera.position = {0.0f, 1.1f, 2.4f};
  s.camera.target = {0, 0, 0};
  s.camera.fov_y_degrees = 50.0f;
  s.camera.near_z = 0.1f;
  s.camera.far_z = 20.0f;
  s.lights = {{normalize(float3{-0.6f, -1.0f, -0.8f}), float3(0.85f)},
              {normalize(float3{0.8f, 0.3f, -0.4f}), float3(0.2f)}};
  s.ambient = float3(0.12f);
}

inline RenderOptions colorAndIds(int width, int height) {
  RenderOptions options;
  options.width = width;
  options.height = height;
  options.depth = false;
  options.ids = true;
  options.lines = false;
  return options;
}

}  // namespace tessera::test
