// decodeExrEnvironment in a build without OpenEXR: a clear refusal.
#include "exr_loader.h"

namespace tessera::io {

Expected<EnvironmentImage> decodeExrEnvironment(const unsigned char*, size_t,
                                                const std::string& name, uint64_t) {
  return makeError(name +
                   ": an OpenEXR image, and this tessera was built without OpenEXR "
                   "(install libopenexr-dev and build again), or convert it to .hdr");
}

}  // namespace tessera::io
