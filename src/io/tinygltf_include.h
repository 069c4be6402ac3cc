// tinygltf, as tessera builds it: no stb_image (images are decoded by image_loader.cpp), no file
// system access (files are opened through gltf_files.h's callbacks). gltf_loader.cpp defines
// TINYGLTF_IMPLEMENTATION before including this; every other file sees the declarations only.
#pragma once

#define TINYGLTF_NO_STB_IMAGE
#define TINYGLTF_NO_STB_IMAGE_WRITE
#define TINYGLTF_NO_EXTERNAL_IMAGE
#define TINYGLTF_NO_FS
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-parameter"
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic ignored "-Wunused-variable"
#pragma GCC diagnostic ignored "-Wsign-compare"
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#pragma GCC diagnostic ignored "-Wimplicit-fallthrough"
#pragma GCC diagnostic ignored "-Wpedantic"
#include <tiny_gltf.h>
#pragma GCC diagnostic pop
