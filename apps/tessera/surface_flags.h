// f3d's --grid, --no-background and --opacity on `render`: a ground grid under the model, a
// transparent background in an RGBA PNG, and a see-through surface; and the environment light
// around the model, --hdri, and the display transform, --tone-mapping and --exposure
// (docs/rendering.md).
#pragma once

#include <cstdint>
#include <string>

#include <tessera/base/expected.h>

#include <tessera/scene/mesh.h>
#include <tessera/scene/scene.h>

#include "flags.h"

namespace tessera::cli {

// --tone-mapping and --exposure (render and view): Scene::tone_mapping and Scene::exposure.
struct ToneSettings {
  std::string tone_mapping = "none";  // none, aces, pbr-neutral
  float exposure = 0.0f;              // stops
};

void addToneFlags(FlagSet& flags, ToneSettings& s);
void applyTone(const ToneSettings& s, Scene& scene);

struct SurfaceSettings {
  bool grid = false;
  bool no_background = false;
  float opacity = 1.0f;
  std::string hdri;              // an equirectangular .hdr: the light around the model
  bool hdri_background = false;  // shown behind the model (f3d's --hdri-skybox)
  ToneSettings tone;
};

void addSurfaceFlags(FlagSet& flags, SurfaceSettings& s);

// "" or why these settings cannot go with the output or each other: --no-background needs a PNG
// (GIF and MP4 have no alpha channel to hold it) of the colour image and no --hdri-background;
// --hdri-background needs --hdri.
std::string refuseSurface(const SurfaceSettings& s, bool png_output, const std::string& aov);

// The grid (along `up`, under the model's `bounds`), the transparent background and the tone
// mapping, on the scene.
void applySurface(const SurfaceSettings& s, const Bounds& bounds, float3 up, Scene& scene);

// --hdri's image read (within `max_pixels`) and prepared, its sky turned to `up`, on the scene.
Expected<void> applyEnvironment(const SurfaceSettings& s, uint64_t max_pixels, float3 up,
                                Scene& scene);

}  // namespace tessera::cli
