// `--light` (repeatable) and `--ambient`: lights given by hand, in the model's world coordinates.
//
//   --light directional:DX,DY,DZ[:R,G,B[:INTENSITY]]
//   --light point:X,Y,Z[:R,G,B[:INTENSITY[:RANGE]]]
//   --light spot:X,Y,Z:DX,DY,DZ:INNER,OUTER[:R,G,B[:INTENSITY[:RANGE]]]
//
// D is the direction the light travels (any length but zero); R,G,B a linear colour (>= 0,
// default 1,1,1); INTENSITY lux (directional) or candela (point, spot), >= 0, default 1; RANGE > 0,
// where KHR_lights_punctual's window ends (default: none); INNER, OUTER the spot's cone half-angles
// in degrees, 0 <= INNER < OUTER <= 90. The units are tessera::Light's (scene.h,
// docs/rendering.md).
#pragma once

#include <string>
#include <vector>

#include <tessera/base/expected.h>
#include <tessera/scene/scene.h>

#include "flags.h"

namespace tessera::cli {

struct LightSettings {
  std::vector<Light> lights;  // --light, in order
  bool ambient_given = false;
  float3 ambient{0.08f, 0.08f, 0.08f};  // --ambient: linear irradiance (the default rig's)
  bool shadows = false;                 // --shadows: shadow maps (RenderOptions::shadows)
};

// One --light value as a Light, or a message saying what is wrong with it.
Expected<Light> parseLight(const std::string& text);

void addLightFlags(FlagSet& flags, LightSettings& settings);

// The scene's lights: `lights` (the file's, then the --light ones) when there are any, else the
// default rig (addViewLights, already in `scene`); the ambient from --ambient when given.
void applyLights(Scene& scene, const std::vector<Light>& lights, const LightSettings& settings);

}  // namespace tessera::cli
