// KHR_draco_mesh_compression in a build without libdraco (TESSERA_DRACO off, or libdraco-dev not
// found): a Draco primitive without an uncompressed fallback is refused (gltf_draco.h).
#include "gltf_draco.h"

namespace tessera::io::gltf {

bool dracoDecoderBuilt() {
  return false;
}

Expected<DracoPrimitive> decodeDracoPrimitive(const tinygltf::Model&, const tinygltf::Primitive&,
                                              const std::string& name, const std::string& where,
                                              const DracoBudget&) {
  return makeError(noDracoDecoder(name + ": " + where));
}

}  // namespace tessera::io::gltf
