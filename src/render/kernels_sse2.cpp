// The kernels compiled for sse2 (CMakeLists.txt gives this file its flags).
// Inline, not always_inline, as in the scalar unit: SSE2 holds an eight-lane value in two
// registers, so each lane operation is twice the code, and forced into whole kernels GCC took
// 90-145 s to compile this file (the Release build's longest); this way it takes 9 s, and the
// frames are within a few percent either way (docs/perf-notes/texturing.md).
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

const Kernels kKernelsSse2 = TESSERA_KERNELS_OF_THIS_ISA;

}  // namespace tessera::render
