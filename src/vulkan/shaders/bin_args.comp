#version 460
// Between setup and binning: the indirect dispatch size of the bin passes (one invocation per
// visible record, 64 to a workgroup), from the count setup appended.
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
#include "common.glsl"
#include "records.glsl"

layout(local_size_x = 1) in;

void main() {
  const uint groups = (counters.visible + 63u) / 64u;
  const uint x = min(groups, 32768u);
  counters.bin_dispatch[0] = x;
  counters.bin_dispatch[1] = x == 0u ? 1u : (groups + x - 1u) / x;
  counters.bin_dispatch[2] = 1u;
}
