// f3d's --grid, --no-background and --opacity on `render`: a ground grid under the model, a
// transparent background in an RGBA PNG, and a see-through surface (docs/usage.md).
#pragma once

#include <string>

#include <tessera/scene/mesh.h>
#include <tessera/scene/scene.h>

#include "flags.h"

namespace tessera::cli {

struct SurfaceSettings {
  bool grid = false;
  bool no_background = false;
  float opacity = 1.0f;
};

void addSurfaceFlags(FlagSet& flags, SurfaceSettings& s);

// "" or why these settings cannot go with the output: --no-background needs a PNG (GIF and MP4
// have no alpha channel to hold it) of the colour image.
std::string refuseSurface(const SurfaceSettings& s, bool png_output, const std::string& aov);

// The grid (along `up`, under the model's `bounds`) and the transparent background, on the scene.
void applySurface(const SurfaceSettings& s, const Bounds& bounds, float3 up, Scene& scene);

}  // namespace tessera::cli
