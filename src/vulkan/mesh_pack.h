// An object's mesh as the shaders read it, for packScene: its vertices with the attributes it
// has, its indices as the IndexPolicy says and its triangles' materials, appended one object after
// another to the packed arrays.
#pragma once

#include <tessera/scene/scene.h>

#include "vulkan/gpu_types.h"
#include "vulkan/scene_upload.h"

namespace tessera::vulkan {

// The object's mesh (which must be set): its counts and attribute flags into `gpu`; its vertices,
// indices and triangles' materials appended to the packed arrays.
void packMesh(const Object& object, IndexPolicy policy, GpuObject& gpu, PackedScene& out);

}  // namespace tessera::vulkan
