// tessera devices: the Vulkan devices and which backends run on each.
#include <iostream>

#ifdef TESSERA_HAVE_VULKAN
#include <tessera/vulkan/vulkan_backend.h>
#endif

#include "commands.h"
#include "flags.h"

namespace tessera::cli {

int runDevices(const std::vector<std::string>& args) {
  FlagSet flags("tessera devices");
  Expected<std::vector<std::string>> positional = flags.parse(args);
  if (flags.helpRequested()) {
    std::cout << flags.usage() << "Lists the Vulkan devices; the number is what --device takes.\n";
    return kExitOk;
  }
  if (!positional || !positional->empty()) {
    printError("devices", positional ? "unexpected argument '" + positional->front() + "'"
                                     : positional.error().message);
    std::cerr << flags.hint();
    return kExitUsage;
  }
#ifdef TESSERA_HAVE_VULKAN
  Expected<std::vector<vulkan::DeviceInfo>> devices = vulkan::listDevices();
  if (!devices) {
    printError("devices", devices.error().message);
    return kExitFailure;
  }
  if (devices->empty()) {
    printError("devices", "the Vulkan loader found no device");
    return kExitFailure;
  }
  for (const vulkan::DeviceInfo& d : *devices) {
    std::cout << d.index << ": " << d.name << " (" << d.type << ", Vulkan " << d.api_version << ", "
              << d.driver << ")\n"
              << "   vulkan:        " << (d.compute_usable ? "yes" : "no") << " (" << d.compute_note
              << ")\n"
              << "   vulkan-raster: " << (d.raster_usable ? "yes" : "no") << " (" << d.raster_note
              << ")\n";
  }
  return kExitOk;
#else
  printError("devices",
             "tessera was built without Vulkan (configure with TESSERA_VULKAN=ON "
             "and the Vulkan headers and glslc installed)");
  return kExitFailure;
#endif
}

}  // namespace tessera::cli
