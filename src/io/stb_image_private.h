// stb_image's implementation, compiled into the translation unit that includes this (static
// linkage: a glTF loader bundling its own copy cannot collide with it), with stb's own warnings
// silenced. The includer first defines the STBI_ONLY_<format> macros of the formats it reads:
// less code that a hostile file can reach. Included once per translation unit, never by headers.
#define STB_IMAGE_IMPLEMENTATION
#define STB_IMAGE_STATIC
// stb's own limit stays far above any budget, so that its header scan reports an image's true
// size and the caller's budget check is what refuses it, with its own message.
#define STBI_MAX_DIMENSIONS (1 << 24)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#pragma GCC diagnostic ignored "-Wsign-compare"
#pragma GCC diagnostic ignored "-Wimplicit-fallthrough"
#pragma GCC diagnostic ignored "-Wunused-parameter"
#pragma GCC diagnostic ignored "-Wdouble-promotion"
#pragma GCC diagnostic ignored "-Wpedantic"
#include <stb_image.h>
#pragma GCC diagnostic pop
