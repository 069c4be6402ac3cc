// The members by their names: none of the header's call macros here.
#define TESSERA_GL_API_NO_MACROS 1
#include "bench/gl_api.h"

#include <dlfcn.h>

#include <mutex>

namespace tessera::bench {

namespace {

GlApi api;

std::string open() {
  // Debian's libosmesa6 (the runtime package of libosmesa6-dev).
  void* library = dlopen("libOSMesa.so.8", RTLD_NOW | RTLD_LOCAL);
  if (!library) library = dlopen("libOSMesa.so", RTLD_NOW | RTLD_LOCAL);
  if (!library)
    return std::string(
               "the llvmpipe reference needs Mesa's OSMesa library (Debian: apt-get "
               "install libosmesa6): ") +
           dlerror();
  GlApi loaded;
  std::string missing;
  const auto find = [&](const char* name) -> void* {
    void* symbol = dlsym(library, name);
    if (!symbol && loaded.OSMesaGetProcAddress)
      symbol = reinterpret_cast<void*>(loaded.OSMesaGetProcAddress(name));
    if (!symbol) missing += std::string(missing.empty() ? "" : ", ") + name;
    return symbol;
  };
#define TESSERA_GL_LOAD(name) loaded.name = reinterpret_cast<decltype(loaded.name)>(find(#name));
  TESSERA_GL_API(TESSERA_GL_LOAD)
#undef TESSERA_GL_LOAD
  if (!missing.empty()) return "libOSMesa lacks " + missing + ": the llvmpipe reference needs them";
  api = loaded;
  return "";
}

}  // namespace

const GlApi& glApi() {
  return api;
}

std::string loadGlApi() {
  static std::once_flag once;
  static std::string result;
  std::call_once(once, [] { result = open(); });
  return result;
}

}  // namespace tessera::bench
