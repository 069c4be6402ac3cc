#include "surface_flags.h"

#include <tessera/model/ground_grid.h>

namespace tessera::cli {

void addSurfaceFlags(FlagSet& flags, SurfaceSettings& s) {
  flags.addSwitch("grid|g", &s.grid, "draw a ground grid under the model, across the up axis");
  flags.addSwitch("no-background", &s.no_background,
                  "a transparent background: an RGBA PNG whose alpha is the model's coverage");
  flags.addFloat("opacity", &s.opacity,
                 "the model's opacity over the background, 0..1 (default 1; the nearest surface "
                 "only: what lies behind it is not drawn)",
                 0.0f, 1.0f);
}

std::string refuseSurface(const SurfaceSettings& s, bool png_output, const std::string& aov) {
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
}

}  // namespace tessera::cli
