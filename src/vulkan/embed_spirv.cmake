# Turns a SPIR-V binary into a header: constexpr uint32_t k<SYMBOL>Spirv[] = {...};
# Usage: cmake -DINPUT=x.spv -DOUTPUT=x.spv.h -DSYMBOL=Name -P embed_spirv.cmake
file(READ ${INPUT} hex HEX)
string(LENGTH "${hex}" hex_length)
math(EXPR remainder "${hex_length} % 8")
if(hex_length EQUAL 0 OR NOT remainder EQUAL 0)
  message(FATAL_ERROR "${INPUT} is not a whole number of 32-bit SPIR-V words")
endif()
# SPIR-V words are little-endian on disk: bytes b0 b1 b2 b3 make the word 0xb3b2b1b0.
string(REGEX REPLACE "(..)(..)(..)(..)" "0x\\4\\3\\2\\1u," words "${hex}")
string(REGEX REPLACE "((0x[0-9a-f]+u,){8})" "\\1\n    " words "${words}")
file(WRITE ${OUTPUT}
  "// Generated from ${INPUT} by embed_spirv.cmake. Do not edit.\n"
  "#pragma once\n#include <cstdint>\n\n"
  "namespace tessera::vulkan::spirv {\n\n"
  "inline constexpr uint32_t k${SYMBOL}[] = {\n    ${words}\n};\n\n"
  "}  // namespace tessera::vulkan::spirv\n")
