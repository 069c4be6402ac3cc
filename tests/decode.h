// Test helpers: decode what tessera wrote (PNG through libpng, GIF through giflib) so tests check
// real files, not our own writer's view of them.
#pragma once

#include <gif_lib.h>
#include <png.h>

#include <array>
#include <cstdint>
#include <cstring>
#include <optional>
#include <string>
#include <vector>

namespace tessera::test {

// The file's own layout, no libpng transforms: what the writer chose is what a test sees.
struct DecodedPng {
  int width = 0, height = 0;
  int channels = 0;               // 1 (grey), 3 (RGB) or 4 (RGBA)
  int bit_depth = 0;              // 8 or 16
  int color_type = -1;            // as stored: PNG_COLOR_TYPE_GRAY, _RGB, _RGB_ALPHA, ...
  std::vector<uint16_t> samples;  // width * height * channels, row 0 first
  uint16_t at(int x, int y, int c) const {
    return samples[(static_cast<size_t>(y) * width + x) * channels + c];
  }
  std::array<int, 3> rgb(int x, int y) const { return {at(x, y, 0), at(x, y, 1), at(x, y, 2)}; }
  std::array<int, 4> rgba(int x, int y) const {
    return {at(x, y, 0), at(x, y, 1), at(x, y, 2), at(x, y, 3)};
  }
  int gray16(int x, int y) const { return at(x, y, 0); }
};

inline bool decodePng(const std::string& path, DecodedPng& out) {
  FILE* file = std::fopen(path.c_str(), "rb");
  if (!file) return false;
  png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  png_infop info = png_create_info_struct(png);
  if (setjmp(png_jmpbuf(png))) {
    png_destroy_read_struct(&png, &info, nullptr);
    std::fclose(file);
    return false;
  }
  png_init_io(png, file);
  png_read_png(png, info, PNG_TRANSFORM_IDENTITY, nullptr);
  out.width = static_cast<int>(png_get_image_width(png, info));
  out.height = static_cast<int>(png_get_image_height(png, info));
  out.channels = png_get_channels(png, info);
  out.bit_depth = png_get_bit_depth(png, info);
  out.color_type = png_get_color_type(png, info);
  png_bytepp rows = png_get_rows(png, info);
  out.samples.resize(static_cast<size_t>(out.width) * out.height * out.channels);
  for (int y = 0; y < out.height; ++y) {
    for (int i = 0; i < out.width * out.channels; ++i) {
      uint16_t v = out.bit_depth == 16
                       ? static_cast<uint16_t>((rows[y][2 * i] << 8) | rows[y][2 * i + 1])
                       : rows[y][i];
      out.samples[static_cast<size_t>(y) * out.width * out.channels + i] = v;
    }
  }
  png_destroy_read_struct(&png, &info, nullptr);
  std::fclose(file);
  return true;
}

inline std::optional<DecodedPng> decodePng(const std::string& path) {
  DecodedPng decoded;
  if (!decodePng(path, decoded)) return std::nullopt;
  return decoded;
}

struct DecodedGif {
  int width = 0, height = 0;
  std::vector<int> delays_cs;                     // per frame
  std::vector<std::vector<uint32_t>> frames_rgb;  // per frame: 0xRRGGBB per pixel
  bool loops = false;
};

inline bool decodeGif(const std::string& path, DecodedGif& out) {
  int error = 0;
  GifFileType* gif = DGifOpenFileName(path.c_str(), &error);
  if (!gif) return false;
  if (DGifSlurp(gif) != GIF_OK) {
    DGifCloseFile(gif, &error);
    return false;
  }
  out.width = gif->SWidth;
  out.height = gif->SHeight;
  std::vector<uint32_t> canvas(static_cast<size_t>(out.width) * out.height, 0);
  for (int i = 0; i < gif->ImageCount; ++i) {
    const SavedImage& image = gif->SavedImages[i];
    GraphicsControlBlock gcb{};
    gcb.DelayTime = 0;
    DGifSavedExtensionToGCB(gif, i, &gcb);
    out.delays_cs.push_back(gcb.DelayTime);
    for (int e = 0; e < image.ExtensionBlockCount; ++e) {
      const ExtensionBlock& b = image.ExtensionBlocks[e];
      if (b.Function == APPLICATION_EXT_FUNC_CODE && b.ByteCount >= 11 &&
          std::memcmp(b.Bytes, "NETSCAPE2.0", 11) == 0)
        out.loops = true;
    }
    const ColorMapObject* map =
        image.ImageDesc.ColorMap ? image.ImageDesc.ColorMap : gif->SColorMap;
    if (!map) return false;
    for (int y = 0; y < image.ImageDesc.Height; ++y)
      for (int x = 0; x < image.ImageDesc.Width; ++x) {
        int index = image.RasterBits[y * image.ImageDesc.Width + x];
        if (gcb.TransparentColor == index) continue;
        const GifColorType c = map->Colors[index];
        canvas[static_cast<size_t>(y + image.ImageDesc.Top) * out.width + x +
               image.ImageDesc.Left] =
            (static_cast<uint32_t>(c.Red) << 16) | (c.Green << 8) | c.Blue;
      }
    out.frames_rgb.push_back(canvas);
  }
  for (int e = 0; e < gif->ExtensionBlockCount; ++e) {
    const ExtensionBlock& b = gif->ExtensionBlocks[e];
    if (b.Function == APPLICATION_EXT_FUNC_CODE && b.ByteCount >= 11 &&
        std::memcmp(b.Bytes, "NETSCAPE2.0", 11) == 0)
      out.loops = true;
  }
  DGifCloseFile(gif, &error);
  return true;
}

}  // namespace tessera::test
