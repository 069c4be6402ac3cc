// OpenEXR environment images through Debian's OpenEXR, read from memory (the bytes were read once
// from a regular file: no second open of a path that may have changed). OpenEXR's own checker
// (checkOpenEXRFile, made for its fuzzing) runs first, so a hostile file is refused before the
// decoder proper reads it; the decoder's exceptions become errors.
#include "exr_loader.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <exception>
#include <vector>

#include <OpenEXR/ImfArray.h>
#include <OpenEXR/ImfCheckFile.h>
#include <OpenEXR/ImfIO.h>
#include <OpenEXR/ImfRgbaFile.h>

#include <tessera/io/image_loader.h>

namespace tessera::io {

namespace {

// The bytes as OpenEXR's input stream.
class MemoryStream : public Imf::IStream {
 public:
  MemoryStream(const unsigned char* data, size_t size, const std::string& name)
      : Imf::IStream(name.c_str()), data_(data), size_(size) {}
  bool read(char c[], int n) override {
    if (n < 0 || static_cast<size_t>(n) > size_ - position_)
      throw std::runtime_error("unexpected end of file");
    std::memcpy(c, data_ + position_, static_cast<size_t>(n));
    position_ += static_cast<size_t>(n);
    return position_ < size_;
  }
  uint64_t tellg() override { return position_; }
  void seekg(uint64_t position) override {
    if (position > size_) throw std::runtime_error("seek past the end of the file");
    position_ = static_cast<size_t>(position);
  }

 private:
  const unsigned char* data_;
  size_t size_;
  size_t position_ = 0;
};

}  // namespace

Expected<EnvironmentImage> decodeExrEnvironment(const unsigned char* data, size_t size,
                                                const std::string& name, uint64_t max_pixels) {
  // reduceMemory and reduceTime: the checker refuses what would take it long or much memory.
  if (Imf::checkOpenEXRFile(reinterpret_cast<const char*>(data), size, /*reduceMemory=*/true,
                            /*reduceTime=*/true))
    return makeError(name + ": the OpenEXR image is corrupt or not one OpenEXR can read");
  try {
    MemoryStream stream(data, size, name);
    Imf::RgbaInputFile file(stream);
    const Imath::Box2i window = file.dataWindow();
    const int64_t width = int64_t{window.max.x} - window.min.x + 1;
    const int64_t height = int64_t{window.max.y} - window.min.y + 1;
    if (width < 2 || height < 1 || width > (1 << 24) || height > (1 << 24))
      return makeError(name + ": an environment image needs at least 2x1 pixels");
    const ImageSize image_size{static_cast<int>(width), static_cast<int>(height)};
    if (image_size.pixels() > max_pixels)
      return makeError(texturePixelsOverBudget(name, image_size, max_pixels));
    Imf::Array2D<Imf::Rgba> pixels(height, width);
    file.setFrameBuffer(&pixels[0][0] - window.min.x - window.min.y * width, 1,
                        static_cast<size_t>(width));
    file.readPixels(window.min.y, window.max.y);
    EnvironmentImage image;
    image.width = image_size.width;
    image.height = image_size.height;
    image.texels.reserve(static_cast<size_t>(image_size.pixels()));
    for (int64_t y = 0; y < height; ++y)
      for (int64_t x = 0; x < width; ++x) {
        const Imf::Rgba& p = pixels[y][x];
        const float3 t{static_cast<float>(p.r), static_cast<float>(p.g), static_cast<float>(p.b)};
        if (!std::isfinite(t.x) || !std::isfinite(t.y) || !std::isfinite(t.z))
          return makeError(name + ": the OpenEXR image holds a non-finite value");
        // Half floats may be slightly negative (ringing of a filter); no light is negative.
        image.texels.push_back({std::max(t.x, 0.0f), std::max(t.y, 0.0f), std::max(t.z, 0.0f)});
      }
    return image;
  } catch (const std::exception& e) {
    return makeError(name + ": cannot read the OpenEXR image: " + e.what());
  }
}

}  // namespace tessera::io
