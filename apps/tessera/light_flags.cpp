#include "light_flags.h"

#include <cmath>
#include <numbers>
#include <sstream>

namespace tessera::cli {

namespace {

std::vector<std::string> splitFields(const std::string& text, char separator) {
  std::vector<std::string> parts;
  std::string part;
  std::stringstream in(text);
  while (std::getline(in, part, separator)) parts.push_back(part);
  if (!text.empty() && text.back() == separator) parts.emplace_back();
  return parts;
}

// A non-negative finite number.
Expected<float> parseNonNegative(const std::string& text, const char* what) {
  float v;
  if (!parseFloatStrict(text, v) || !std::isfinite(v) || v < 0.0f)
    return makeError(std::string(what) + " must be a number >= 0, got '" + text + "'");
  return v;
}

Expected<float3> parseDirection(const std::string& text) {
  Expected<float3> d = parseFloat3(text);
  if (!d) return makeError("direction: " + d.error().message);
  if (dot(*d, *d) == 0.0f || !std::isfinite(dot(*d, *d)))
    return makeError("the direction '" + text + "' has no length");
  return normalize(*d);
}

// The optional tail R,G,B[:INTENSITY[:RANGE]] from fields[first].
Expected<void> parseTail(const std::vector<std::string>& fields, size_t first, bool has_range,
                         Light& light) {
  const size_t most = first + (has_range ? 3 : 2);
  if (fields.size() > most)
    return makeError("too many ':' fields (at most " + std::to_string(most) + ")");
  if (fields.size() > first) {
    Expected<float3> c = parseFloat3(fields[first]);
    if (!c) return makeError("colour: " + c.error().message);
    if (c->x < 0.0f || c->y < 0.0f || c->z < 0.0f)
      return makeError("colour channels must be >= 0, got '" + fields[first] + "'");
    light.color = *c;
  }
  if (fields.size() > first + 1) {
    Expected<float> i = parseNonNegative(fields[first + 1], "intensity");
    if (!i) return i.error();
    light.intensity = *i;
  }
  if (fields.size() > first + 2) {
    Expected<float> r = parseNonNegative(fields[first + 2], "range");
    if (!r) return r.error();
    if (*r == 0.0f) return makeError("range must be > 0 (leave it out for none)");
    light.range = *r;
  }
  return {};
}

Expected<void> parseCone(const std::string& text, Light& light) {
  const std::vector<std::string> angles = splitFields(text, ',');
  float inner, outer;
  if (angles.size() != 2 || !parseFloatStrict(angles[0], inner) ||
      !parseFloatStrict(angles[1], outer))
    return makeError("the cone must be INNER,OUTER in degrees, got '" + text + "'");
  if (!(inner >= 0.0f && outer > inner && outer <= 90.0f))
    return makeError("the cone must have 0 <= INNER < OUTER <= 90 degrees, got '" + text + "'");
  const float to_radians = std::numbers::pi_v<float> / 180.0f;
  light.inner_cone = inner * to_radians;
  light.outer_cone = outer * to_radians;
  return {};
}

Expected<Light> parseLightFields(const std::vector<std::string>& fields) {
  const std::string& type = fields[0];
  Light light;
  if (type == "directional") {
    if (fields.size() < 2) return makeError("directional needs a direction: directional:DX,DY,DZ");
    Expected<float3> d = parseDirection(fields[1]);
    if (!d) return d.error();
    light.direction = *d;
    if (Expected<void> ok = parseTail(fields, 2, false, light); !ok) return ok.error();
    return light;
  }
  if (type == "point" || type == "spot") {
    const bool spot = type == "spot";
    light.type = spot ? LightType::kSpot : LightType::kPoint;
    if (fields.size() < (spot ? 4u : 2u))
      return makeError(spot ? "spot needs spot:X,Y,Z:DX,DY,DZ:INNER,OUTER"
                            : "point needs a position: point:X,Y,Z");
    Expected<float3> p = parseFloat3(fields[1]);
    if (!p) return makeError("position: " + p.error().message);
    light.position = *p;
    if (spot) {
      Expected<float3> d = parseDirection(fields[2]);
      if (!d) return d.error();
      light.direction = *d;
      if (Expected<void> ok = parseCone(fields[3], light); !ok) return ok.error();
    }
    if (Expected<void> ok = parseTail(fields, spot ? 4 : 2, true, light); !ok) return ok.error();
    return light;
  }
  return makeError("the type must be directional, point or spot, got '" + type + "'");
}

}  // namespace

Expected<Light> parseLight(const std::string& text) {
  Expected<Light> light = parseLightFields(splitFields(text, ':'));
  if (!light) return makeError("--light '" + text + "': " + light.error().message);
  return light;
}

void addLightFlags(FlagSet& flags, LightSettings& settings) {
  flags.addCustom(
      "light", "TYPE:...",
      "add a light (repeatable; replaces the default rig): directional:DX,DY,DZ[:R,G,B[:LUX]], "
      "point:X,Y,Z[:R,G,B[:CANDELA[:RANGE]]], "
      "spot:X,Y,Z:DX,DY,DZ:INNER,OUTER[:R,G,B[:CANDELA[:RANGE]]] (world coordinates, linear "
      "colour, cone angles in degrees; docs/rendering.md)",
      [&settings](const std::string& v) -> std::string {
        Expected<Light> light = parseLight(v);
        if (!light) return light.error().message;
        settings.lights.push_back(*light);
        return "";
      });
  flags.addCustom("ambient", "R,G,B", "ambient irradiance, linear (default 0.08,0.08,0.08)",
                  [&settings](const std::string& v) -> std::string {
                    Expected<float3> a = parseFloat3(v);
                    if (!a) return a.error().message;
                    if (a->x < 0.0f || a->y < 0.0f || a->z < 0.0f)
                      return "--ambient channels must be >= 0";
                    settings.ambient = *a;
                    settings.ambient_given = true;
                    return "";
                  });
  flags.addSwitch("shadows", &settings.shadows,
                  "shadow maps for directional and spot lights, on smooth and pbr shading");
}

void applyLights(Scene& scene, const std::vector<Light>& lights, const LightSettings& settings) {
  if (!lights.empty()) scene.lights = lights;
  if (settings.ambient_given) scene.ambient = settings.ambient;
}

}  // namespace tessera::cli
