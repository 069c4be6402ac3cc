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

namespace {

std::vector<std::string> simdNames() {
  return {"auto", "scalar", "sse2", "avx2", "avx512"};
}

// The cpu backend on the kernels `simd` names; an error where the CPU cannot run them (the
// renderer would fall back to the widest it can: a benchmark must not time other kernels than
// those asked for).
Expected<std::unique_ptr<Backend>> makeCpuBackend(int workers, const std::string& simd) {
  const std::vector<std::string> names = simdNames();
  const SimdLevel levels[] = {SimdLevel::kAuto, SimdLevel::kScalar, SimdLevel::kSse2,
                              SimdLevel::kAvx2, SimdLevel::kAvx512};
  SimdLevel level = SimdLevel::kAuto;
  for (size_t i = 0; i < names.size(); ++i)
    if (names[i] == simd) level = levels[i];
  auto renderer = std::make_unique<CpuRenderer>(workers, level);
  if (level != SimdLevel::kAuto && simd != renderer->simdName())
    return makeError("--simd " + simd + ": this CPU cannot run those kernels (its widest: " +
                     renderer->simdName() + ")");
  return std::unique_ptr<Backend>(std::move(renderer));
}

}  // namespace

void addSimdFlag(FlagSet& flags, std::string* simd) {
  flags.addChoice(
      "simd", simd, simdNames(),
      "the cpu backend's kernels: auto (the widest this CPU runs, the default), scalar, "
      "sse2, avx2 or avx512; every choice draws the same image");
}

std::string refuseSimd(const std::string& simd, const std::string& backend) {
  if (simd == "auto" || backend == "cpu") return "";
  return "--simd chooses the cpu backend's kernels: leave it out with --backend " + backend;
}

std::string simdName(const Backend& backend) {
  const auto* cpu = dynamic_cast<const CpuRenderer*>(&backend);
  return cpu != nullptr ? cpu->simdName() : "";
}

Expected<std::unique_ptr<Backend>> makeBackend(const std::string& name, int workers, int device,
                                               const std::string& simd) {
  if (name == "cpu") return makeCpuBackend(workers, simd);
  if (std::string refused = refuseSimd(simd, name); !refused.empty()) return makeError(refused);
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
