#include "render/kernels.h"

namespace tessera::render {

Isa detectIsa() {
#if defined(__x86_64__) || defined(__i386__)
  __builtin_cpu_init();
  if (__builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512vl") &&
      __builtin_cpu_supports("avx512bw") && __builtin_cpu_supports("avx512dq"))
    return Isa::kAvx512;
  if (__builtin_cpu_supports("avx2")) return Isa::kAvx2;
  return Isa::kSse2;
#else
  return Isa::kScalar;
#endif
}

const char* isaName(Isa isa) {
  switch (isa) {
    case Isa::kScalar:
      return "scalar";
    case Isa::kSse2:
      return "sse2";
    case Isa::kAvx2:
      return "avx2";
    case Isa::kAvx512:
      return "avx512";
  }
  return "?";
}

TileKernels tileKernels(Isa isa) {
  switch (isa) {
    case Isa::kScalar:
      return kTileKernelsScalar;
#if defined(__x86_64__) || defined(__i386__)
    case Isa::kSse2:
      return kTileKernelsSse2;
    case Isa::kAvx2:
      return kTileKernelsAvx2;
    case Isa::kAvx512:
      return kTileKernelsAvx512;
#else
    default:
      return kTileKernelsScalar;
#endif
  }
  return kTileKernelsScalar;
}

SetupKernels setupKernels(Isa isa) {
  switch (isa) {
    case Isa::kScalar:
      return kSetupKernelsScalar;
#if defined(__x86_64__) || defined(__i386__)
    case Isa::kSse2:
      return kSetupKernelsSse2;
    case Isa::kAvx2:
      return kSetupKernelsAvx2;
    case Isa::kAvx512:
      return kSetupKernelsAvx512;
#else
    default:
      return kSetupKernelsScalar;
#endif
  }
  return kSetupKernelsScalar;
}

}  // namespace tessera::render
