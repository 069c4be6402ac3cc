#include "backends.h"

#include <iostream>

#include <tessera/render/cpu_renderer.h>
#ifdef TESSERA_HAVE_VULKAN
#include <tessera/vulkan/vulkan_backend.h>
#endif

namespace tessera::cli {

std::vector<std::string> backendNames() {
#ifdef TESSERA_HAVE_VULKAN
  return {"cpu", "vulkan", "vulkan-raster"};
#else
  return {"cpu"};
#endif
}

Expected<std::unique_ptr<Backend>> makeBackend(const std::string& name, int workers, int device) {
  if (name == "cpu") return std::unique_ptr<Backend>(std::make_unique<CpuRenderer>(workers));
#ifdef TESSERA_HAVE_VULKAN
  vulkan::VulkanOptions options;
  options.device = device;
  if (name == "vulkan") {
    Expected<std::unique_ptr<vulkan::ComputeBackend>> backend =
        vulkan::ComputeBackend::create(options);
    if (!backend) return backend.error();
    // Say which fallback a device takes, once.
    if (!(*backend)->device().int64_atomics || !(*backend)->device().float64)
      std::cerr << "tessera: vulkan: " << (*backend)->device().name << ": "
                << (*backend)->device().compute_note << "\n";
    return std::unique_ptr<Backend>(std::move(*backend));
  }
  if (name == "vulkan-raster") return vulkan::makeRasterBackend(options);
#else
  (void)device;
  if (name == "vulkan" || name == "vulkan-raster")
    return makeError("backend '" + name + "' is not available: tessera was built without Vulkan");
#endif
  return makeError("unknown backend '" + name + "'");
}

std::string vulkanCommitPath(Backend& backend, bool toggle) {
#ifdef TESSERA_HAVE_VULKAN
  auto* compute = dynamic_cast<vulkan::ComputeBackend*>(&backend);
  if (compute == nullptr) return "";
  if (!compute->device().int64_atomics)
    return "commit path: 32-bit (the device has no 64-bit atomics)";
  std::string failed;
  if (toggle) {
    if (Expected<void> set = compute->setForce32BitAtomics(compute->uses64BitCommits()); !set)
      failed = " (cannot switch: " + set.error().message + ")";
  }
  return std::string("commit path: ") +
         (compute->uses64BitCommits() ? "64-bit atomics" : "32-bit, two passes") + failed;
#else
  (void)backend, (void)toggle;
  return "";
#endif
}

}  // namespace tessera::cli
