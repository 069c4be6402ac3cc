#include "surface_flags.h"

#include <algorithm>
#include <cmath>
#include <memory>

#include <tessera/io/image_loader.h>
#include <tessera/model/ground_grid.h>

namespace tessera::cli {

void addToneFlags(FlagSet& flags, ToneSettings& s) {
  flags.addChoice("tone-mapping", &s.tone_mapping, {"none", "aces", "pbr-neutral"},
                  "map the shaded light into the display's range before the sRGB encode: none "
                  "(clip at 1; default), aces (ACES filmic) or pbr-neutral (Khronos PBR Neutral)");
  flags.addFloat("exposure", &s.exposure,
                 "scale the shaded light by 2^EV before the tone mapping, in stops (default 0)",
                 -20.0f, 20.0f);
}

void applyTone(const ToneSettings& s, Scene& scene) {
  scene.tone_mapping = s.tone_mapping == "aces"          ? ToneMapping::kAces
                       : s.tone_mapping == "pbr-neutral" ? ToneMapping::kPbrNeutral
                                                         : ToneMapping::kNone;
  scene.exposure = s.exposure;
}

void addSurfaceFlags(FlagSet& flags, SurfaceSettings& s) {
  flags.addSwitch("grid|g", &s.grid, "draw a ground grid under the model, across the up axis");
  flags.addSwitch("no-background", &s.no_background,
                  "a transparent background: an RGBA PNG whose alpha is the model's coverage");
  flags.addFloat("opacity", &s.opacity,
                 "the model's opacity over the background, 0..1 (default 1; the nearest surface "
                 "only: what lies behind it is not drawn)",
                 0.0f, 1.0f);
  flags.addString(
      "hdri", &s.hdri,
      "an equirectangular Radiance .hdr or OpenEXR .exr image as the light around the model "
      "(image-based lighting in --shading pbr)");
  flags.addSwitch("hdri-background|hdri-skybox", &s.hdri_background,
                  "show the --hdri image behind the model");
  addToneFlags(flags, s.tone);
}

std::string refuseSurface(const SurfaceSettings& s, bool png_output, const std::string& aov) {
  if (s.hdri_background && s.hdri.empty()) return "--hdri-background needs an image: --hdri PATH";
  if (s.hdri_background && s.no_background)
    return "--hdri-background and --no-background ask for two different backgrounds";
  if (!s.no_background) return "";
  if (!png_output)
    return "--no-background writes an RGBA PNG: GIF and MP4 have no alpha channel (use a .png or "
           "a {frame} .png output)";
  if (aov != "color") return "--no-background is for the colour image: leave out --aov " + aov;
  return "";
}

void applySurface(const SurfaceSettings& s, const Bounds& bounds, float3 up, Scene& scene) {
  if (s.grid) model::appendGroundGrid(bounds, up, scene.lines);
  if (s.no_background) scene.background = {0.0f, 0.0f, 0.0f, 0.0f};
  applyTone(s.tone, scene);
}

namespace {

// The rotation taking unit vector `up` to +Y (the environment image's up), by the shortest arc.
float3x3 rotationToYUp(float3 up) {
  const float3 y{0, 1, 0};
  const float c = dot(up, y);
  if (c > 0.9999f) return float3x3{};
  const float3 axis = c < -0.9999f ? float3{1, 0, 0} : normalize(cross(up, y));
  return toMatrix3(quat::fromAxisAngle(axis, std::acos(std::clamp(c, -1.0f, 1.0f))));
}

}  // namespace

Expected<void> applyEnvironment(const SurfaceSettings& s, uint64_t max_pixels, float3 up,
                                Scene& scene) {
  if (s.hdri.empty()) return {};
  Expected<EnvironmentImage> image = io::loadEnvironmentImage(s.hdri, max_pixels);
  if (!image) return image.error();
  scene.environment = std::make_shared<const Environment>(std::move(*image));
  scene.environment_background = s.hdri_background;
  scene.world_to_environment = rotationToYUp(normalize(up));
  return {};
}

}  // namespace tessera::cli
