// tessera render's settings, as its flags set them (cmd_render.cpp), shared with the scene's
// loading (render_scene.cpp).
#pragma once

#include <optional>
#include <string>

#include <tessera/io/model_loader.h>
#include <tessera/model/camera_setup.h>

#include "light_flags.h"
#include "point_flags.h"
#include "progress.h"
#include "sampling_flags.h"
#include "surface_flags.h"
#include "validation.h"

namespace tessera::cli {

struct RenderSettings {
  std::string output;
  int width = 1000, height = 600;
  float3 background{0.2f, 0.2f, 0.2f};
  std::optional<float3> color;  // --color: the default material's, sRGB
  model::CameraSettings camera;
  std::string shading;   // empty: defaultShading (pbr for glTF, else smooth)
  std::string backface;  // empty: the model says (glTF doubleSided), else visible
  std::string aov = "color";
  std::string backend = "cpu";
  std::string simd = "auto";
  int turntable = 0;
  float duration = 0.0f;  // --duration SECONDS: the turntable's length, 0 when not given
  int fps = 30;
  int animation_index = -1;  // --animation-index: the glTF clip to play, -1 none
  std::string frame_range;   // --frame-range A:B, frames of the clip at --fps
  int workers = 0;
  int device = -1;
  bool axes = false;
  bool info = false;
  std::string texture;
  bool crc = false;
  ReferenceSettings reference;
  std::string stats;      // --stats PATH.json: the frames' diagnostics (docs/stats.md)
  io::LoadBudget budget;  // --memory-limit, --max-triangles, --max-texture-pixels
  SamplingSettings sampling{.msaa = 4};  // the image a user expects: anti-aliased
  std::string visibility = "z-buffer";
  bool edges = false;
  float3 edge_color{0, 0, 0};  // sRGB
  PointSettings points;        // --point-size, --point-sprites, --line-width
  LightSettings lights;        // --light, --ambient
  ProgressFlags progress;      // --quiet, --progress
  SurfaceSettings surface;     // --grid, --no-background, --opacity
};

}  // namespace tessera::cli
