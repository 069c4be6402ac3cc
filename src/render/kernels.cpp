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

Isa isaFor(SimdLevel level) {
  const Isa best = detectIsa();
  switch (level) {
    case SimdLevel::kAuto:
      return best;
    case SimdLevel::kScalar:
      return Isa::kScalar;
    case SimdLevel::kSse2:
      return best >= Isa::kSse2 ? Isa::kSse2 : best;
    case SimdLevel::kAvx2:
      return best >= Isa::kAvx2 ? Isa::kAvx2 : best;
    case SimdLevel::kAvx512:
      return best;
  }
  return best;
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

Kernels kernelsFor(Isa isa) {
  switch (isa) {
    case Isa::kScalar:
      return kKernelsScalar;
#if defined(__x86_64__) || defined(__i386__)
#if TESSERA_LEAN_KERNELS  // sanitizer builds: CMakeLists.txt's TESSERA_LEAN_KERNELS
    case Isa::kSse2:
      return kKernelsScalar;
    case Isa::kAvx2:
    case Isa::kAvx512:
      return kKernelsAvx2;
#else
    case Isa::kSse2:
      return kKernelsSse2;
    case Isa::kAvx2:
      return kKernelsAvx2;
    case Isa::kAvx512:
      return kKernelsAvx512;
#endif
#else
    default:
      return kKernelsScalar;
#endif
  }
  return kKernelsScalar;
}

}  // namespace tessera::render
