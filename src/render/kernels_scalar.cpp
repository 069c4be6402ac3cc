// The kernels compiled for scalar (CMakeLists.txt gives this file its flags).
#define TESSERA_SIMD_SCALAR 1  // the lanes are plain arrays
// Inline, not always_inline: GCC then keeps a call where a body would make a kernel huge. Forced
// into whole kernels, the eight-iteration loops of every lane operation took GCC 16 minutes to
// compile at -O2 (11 of them in tree PRE), and -O1 2m46s; this way it takes 16 s.
#define TESSERA_LANES_INLINE inline
#include "render/blend_kernel.h"
#include "render/kernels.h"
#include "render/painter_kernel.h"
#include "render/raster_kernel.h"
#include "render/raster_samples_kernel.h"
#include "render/ray_kernel.h"
#include "render/setup_kernel.h"
#include "render/shade_kernel.h"
#include "render/vertex_kernel.h"

namespace tessera::render {

const Kernels kKernelsScalar = TESSERA_KERNELS_OF_THIS_ISA;

}  // namespace tessera::render
