// The kernels compiled for avx512 (CMakeLists.txt gives this file its flags).
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

const Kernels kKernelsAvx512 = TESSERA_KERNELS_OF_THIS_ISA;

}  // namespace tessera::render
