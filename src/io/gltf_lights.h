// glTF KHR_lights_punctual: the lights a node carries, placed in world space. Private to
// tessera_io; one call from the node traversal (gltf_loader.cpp).
#pragma once

#include <cstddef>
#include <vector>

#include <tessera/scene/scene.h>

#include "gltf_nodes.h"
#include "gltf_transforms.h"

namespace tessera::io::gltf {

// Appends the light node `index` refers to (its KHR_lights_punctual extension), at the node's
// global matrix: position its origin, direction its -Z (scale ignored, as the extension says).
// A light the file describes badly (unknown type, negative intensity, a cone outside
// 0 <= inner < outer <= pi/2, a colour that is not three finite non-negative numbers, an index
// past the file's lights) is skipped with a warning naming it; a bad range is ignored (infinite).
void addNodeLight(const tinygltf::Model& gltf, const tinygltf::Node& node, size_t index,
                  const Matrix& global, const Warn& warn, std::vector<Light>& out);

}  // namespace tessera::io::gltf
