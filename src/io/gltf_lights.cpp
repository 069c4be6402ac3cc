#include "gltf_lights.h"

#include <cmath>
#include <numbers>
#include <optional>
#include <string>

#include "tinygltf_include.h"

namespace tessera::io::gltf {

namespace {

// The light index of the node's KHR_lights_punctual extension; none when it has none, with a
// warning when the extension is malformed.
std::optional<size_t> nodeLightIndex(const tinygltf::Model& gltf, const tinygltf::Node& node,
                                     const std::string& where, const Warn& warn) {
  const auto it = node.extensions.find("KHR_lights_punctual");
  if (it == node.extensions.end()) return std::nullopt;
  const tinygltf::Value& extension = it->second;
  if (!extension.IsObject() || !extension.Has("light") || !extension.Get("light").IsInt()) {
    warn(where + ": KHR_lights_punctual has no integer \"light\"; no light is placed");
    return std::nullopt;
  }
  const int light = extension.Get("light").GetNumberAsInt();
  if (light < 0 || static_cast<size_t>(light) >= gltf.lights.size()) {
    warn(where + " refers to light " + std::to_string(light) + ", but the file has " +
         std::to_string(gltf.lights.size()) + " lights; it is skipped");
    return std::nullopt;
  }
  return static_cast<size_t>(light);
}

// The light's own fields (no placement), or none with a warning saying what is wrong.
std::optional<Light> lightFields(const tinygltf::Light& in, const std::string& where,
                                 const Warn& warn) {
  Light light;
  if (in.type == "directional") {
    light.type = LightType::kDirectional;
  } else if (in.type == "point") {
    light.type = LightType::kPoint;
  } else if (in.type == "spot") {
    light.type = LightType::kSpot;
  } else {
    warn(where + " has the unknown type \"" + in.type + "\"; it is skipped");
    return std::nullopt;
  }
  if (!in.color.empty()) {
    if (in.color.size() != 3) {
      warn(where + ": color has " + std::to_string(in.color.size()) +
           " components, not 3; it is skipped");
      return std::nullopt;
    }
    for (int k = 0; k < 3; ++k) {
      const double c = in.color[static_cast<size_t>(k)];
      if (!std::isfinite(c) || c < 0.0) {
        warn(where + ": color has a negative or non-finite component; it is skipped");
        return std::nullopt;
      }
      light.color[k] = static_cast<float>(c);
    }
  }
  if (!std::isfinite(in.intensity) || in.intensity < 0.0) {
    warn(where + ": intensity " + std::to_string(in.intensity) +
         " is negative or not finite; it is skipped");
    return std::nullopt;
  }
  light.intensity = toFloat(in.intensity);
  if (light.type != LightType::kDirectional && in.range != 0.0) {
    if (std::isfinite(in.range) && in.range > 0.0)
      light.range = toFloat(in.range);
    else
      warn(where + ": range " + std::to_string(in.range) + " is not positive; the light has none");
  }
  if (light.type == LightType::kSpot) {
    const double inner = in.spot.innerConeAngle, outer = in.spot.outerConeAngle;
    if (!(inner >= 0.0 && outer > inner && outer <= std::numbers::pi / 2)) {
      warn(where + ": the spot's cone (innerConeAngle " + std::to_string(inner) +
           ", outerConeAngle " + std::to_string(outer) +
           ") is not 0 <= inner < outer <= pi/2; it is skipped");
      return std::nullopt;
    }
    light.inner_cone = static_cast<float>(inner);
    light.outer_cone = static_cast<float>(outer);
  }
  return light;
}

}  // namespace

void addNodeLight(const tinygltf::Model& gltf, const tinygltf::Node& node, size_t index,
                  const Matrix& global, const Warn& warn, std::vector<Light>& out) {
  const std::string where = "node " + std::to_string(index);
  const std::optional<size_t> light_index = nodeLightIndex(gltf, node, where, warn);
  if (!light_index) return;
  const std::string what = "light " + std::to_string(*light_index);
  std::optional<Light> light = lightFields(gltf.lights[*light_index], what, warn);
  if (!light) return;
  // The node's origin and its -Z axis (the third column, negated).
  const float3 position{toFloat(global.at(0, 3)), toFloat(global.at(1, 3)),
                        toFloat(global.at(2, 3))};
  const float3 axis{toFloat(-global.at(0, 2)), toFloat(-global.at(1, 2)),
                    toFloat(-global.at(2, 2))};
  const float3 direction = normalize(axis);
  const bool placed = std::isfinite(position.x) && std::isfinite(position.y) &&
                      std::isfinite(position.z) && dot(direction, direction) > 0.0f;
  if (!placed) {
    warn(what + " (at " + where +
         "): the node's transform is degenerate or not finite; it is "
         "skipped");
    return;
  }
  light->position = position;
  light->direction = direction;
  out.push_back(*light);
}

}  // namespace tessera::io::gltf
