#include "backends.h"

#include <tessera/render/cpu_renderer.h>

namespace tessera::cli {

std::vector<std::string> backendNames() {
  return {"cpu"};
}

Expected<std::unique_ptr<Backend>> makeBackend(const std::string& name, int workers, int device) {
  (void)device;
  if (name == "cpu") return std::unique_ptr<Backend>(std::make_unique<CpuRenderer>(workers));
  return makeError("unknown backend '" + name + "'");
}

}  // namespace tessera::cli
