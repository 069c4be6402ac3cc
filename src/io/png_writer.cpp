#include <tessera/io/image_writer.h>

#include <spng.h>

#include <cmath>
#include <cstring>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "writer_internal.h"

namespace tessera::io {
namespace {

// The largest value an RGB8 id image can hold: 24 bits.
constexpr uint32_t kMaxEncodableId = 0xFFFFFF;

struct SpngDeleter {
  void operator()(spng_ctx* ctx) const { spng_ctx_free(ctx); }
};
using SpngContext = std::unique_ptr<spng_ctx, SpngDeleter>;

struct PngStream {
  AtomicFile* file;
  std::optional<Error> error;  // the OS reason, which spng would reduce to SPNG_IO_ERROR
};

int writeToStream(spng_ctx* /*ctx*/, void* user, void* data, size_t length) {
  auto* stream = static_cast<PngStream*>(user);
  Expected<void> written = stream->file->write(data, length);
  if (written) return 0;
  stream->error = written.error();
  return SPNG_IO_ERROR;
}

struct PngLayout {
  uint8_t color_type;
  uint8_t bit_depth;
  int channels;
};
constexpr PngLayout kRgb8{SPNG_COLOR_TYPE_TRUECOLOR, 8, 3};
constexpr PngLayout kRgba8{SPNG_COLOR_TYPE_TRUECOLOR_ALPHA, 8, 4};
constexpr PngLayout kGray16{SPNG_COLOR_TYPE_GRAYSCALE, 16, 1};
constexpr PngLayout kGray8{SPNG_COLOR_TYPE_GRAYSCALE, 8, 1};

// Encodes row by row: fill_row(y, row) fills one row in the layout's format (16-bit samples in
// host byte order, which SPNG_FMT_PNG converts), so no whole-image copy is ever made.
template <typename FillRow>
Expected<void> encodePng(AtomicFile& file, int width, int height, const PngLayout& layout,
                         FillRow&& fill_row) {
  TESSERA_CHECK(width > 0 && height > 0) << "PNG of " << width << "x" << height;
  auto failure = [&](const char* step, int code) {
    return makeError("cannot encode PNG '" + file.target().string() + "': " + step + ": " +
                     spng_strerror(code));
  };

  SpngContext ctx(spng_ctx_new(SPNG_CTX_ENCODER));
  if (!ctx) return makeError("cannot encode PNG '" + file.target().string() + "': out of memory");
  PngStream stream{&file, std::nullopt};
  if (int code = spng_set_png_stream(ctx.get(), writeToStream, &stream)) {
    return failure("output", code);
  }
  spng_ihdr ihdr{};
  ihdr.width = static_cast<uint32_t>(width);
  ihdr.height = static_cast<uint32_t>(height);
  ihdr.bit_depth = layout.bit_depth;
  ihdr.color_type = layout.color_type;
  if (int code = spng_set_ihdr(ctx.get(), &ihdr)) return failure("header", code);
  if (int code = spng_encode_image(ctx.get(), nullptr, 0, SPNG_FMT_PNG,
                                   SPNG_ENCODE_PROGRESSIVE | SPNG_ENCODE_FINALIZE)) {
    if (stream.error) return *stream.error;
    return failure("start", code);
  }

  const size_t row_bytes = static_cast<size_t>(width) * layout.channels * (layout.bit_depth / 8);
  std::vector<uint8_t> row(row_bytes);
  for (int y = 0; y < height; ++y) {
    fill_row(y, row.data());
    int code = spng_encode_row(ctx.get(), row.data(), row.size());
    // SPNG_EOI marks the last row, after which the PNG has been finalized.
    if (code == SPNG_EOI && y == height - 1) break;
    if (code != SPNG_OK) {
      if (stream.error) return *stream.error;
      return failure("row", code);
    }
  }
  return {};
}

template <typename Encode>
Expected<void> writeAtomically(const std::filesystem::path& path, Encode&& encode) {
  Expected<AtomicFile> file = AtomicFile::create(path);
  if (!file) return file.error();
  if (Expected<void> encoded = encode(*file); !encoded) return encoded;
  return file->commit();
}

void storeGray16(uint8_t* out, uint16_t value) {
  std::memcpy(out, &value, sizeof(value));
}

uint16_t depthToGray16(float z) {
  if (!(z < 1.0f)) return 65535;  // also +inf (nothing drawn) and NaN
  if (!(z > 0.0f)) return 0;
  return static_cast<uint16_t>(std::lround(static_cast<double>(z) * 65535.0));
}

uint8_t unitToByte(float v) {
  if (!(v > 0.0f)) return 0;
  if (v >= 1.0f) return 255;
  return static_cast<uint8_t>(std::lround(v * 255.0f));
}

void checkFrameBuffer(const Frame& frame, size_t buffer_size, const char* name) {
  TESSERA_CHECK(frame.width > 0 && frame.height > 0)
      << "AOV of a " << frame.width << "x" << frame.height << " frame";
  TESSERA_CHECK(buffer_size == frame.pixelCount())
      << "frame." << name << " holds " << buffer_size << " values for " << frame.pixelCount()
      << " pixels";
}

}  // namespace

Expected<void> encodePngRgba8(AtomicFile& file, int width, int height, const uint32_t* pixels,
                              bool keep_alpha) {
  TESSERA_CHECK(pixels != nullptr) << "no pixels for " << file.target();
  const size_t row_pixels = static_cast<size_t>(width);
  // Shifts rather than a byte copy: "R in the low byte" is a property of the value, whatever
  // the host's byte order.
  if (keep_alpha) {
    return encodePng(file, width, height, kRgba8, [&](int y, uint8_t* row) {
      const uint32_t* in = pixels + static_cast<size_t>(y) * row_pixels;
      for (size_t x = 0; x < row_pixels; ++x) {
        row[4 * x + 0] = static_cast<uint8_t>(in[x]);
        row[4 * x + 1] = static_cast<uint8_t>(in[x] >> 8);
        row[4 * x + 2] = static_cast<uint8_t>(in[x] >> 16);
        row[4 * x + 3] = static_cast<uint8_t>(in[x] >> 24);
      }
    });
  }
  return encodePng(file, width, height, kRgb8, [&](int y, uint8_t* row) {
    const uint32_t* in = pixels + static_cast<size_t>(y) * row_pixels;
    for (size_t x = 0; x < row_pixels; ++x) {
      row[3 * x + 0] = static_cast<uint8_t>(in[x]);
      row[3 * x + 1] = static_cast<uint8_t>(in[x] >> 8);
      row[3 * x + 2] = static_cast<uint8_t>(in[x] >> 16);
    }
  });
}

Expected<void> writePngRgba8(const std::filesystem::path& path, int width, int height,
                             const uint32_t* pixels, bool keep_alpha) {
  return writeAtomically(path, [&](AtomicFile& file) {
    return encodePngRgba8(file, width, height, pixels, keep_alpha);
  });
}

Expected<void> writePngGray16(const std::filesystem::path& path, int width, int height,
                              const uint16_t* pixels) {
  TESSERA_CHECK(pixels != nullptr) << "no pixels for " << path;
  return writeAtomically(path, [&](AtomicFile& file) {
    return encodePng(file, width, height, kGray16, [&](int y, uint8_t* row) {
      std::memcpy(row, pixels + static_cast<size_t>(y) * width, sizeof(uint16_t) * width);
    });
  });
}

Expected<void> writeIdPng(const std::filesystem::path& path, const Frame& frame) {
  checkFrameBuffer(frame, frame.triangle_id.size(), "triangle_id");
  for (uint32_t id : frame.triangle_id) {
    if (id > kMaxEncodableId) {
      return makeError("cannot write '" + path.string() + "': triangle id " + std::to_string(id) +
                       " does not fit the 24 bits of an RGB8 id image");
    }
  }
  return writeAtomically(path, [&](AtomicFile& file) {
    return encodePng(file, frame.width, frame.height, kRgb8, [&](int y, uint8_t* row) {
      const uint32_t* in = frame.triangle_id.data() + static_cast<size_t>(y) * frame.width;
      for (int x = 0; x < frame.width; ++x) {
        row[3 * x + 0] = static_cast<uint8_t>(in[x]);
        row[3 * x + 1] = static_cast<uint8_t>(in[x] >> 8);
        row[3 * x + 2] = static_cast<uint8_t>(in[x] >> 16);
      }
    });
  });
}

Expected<void> writeDepthPng(const std::filesystem::path& path, const Frame& frame) {
  checkFrameBuffer(frame, frame.depth.size(), "depth");
  return writeAtomically(path, [&](AtomicFile& file) {
    return encodePng(file, frame.width, frame.height, kGray16, [&](int y, uint8_t* row) {
      const float* in = frame.depth.data() + static_cast<size_t>(y) * frame.width;
      for (int x = 0; x < frame.width; ++x) storeGray16(row + 2 * x, depthToGray16(in[x]));
    });
  });
}

Expected<void> writeNormalPng(const std::filesystem::path& path, const Frame& frame) {
  if (frame.normal.empty()) {
    return makeError("cannot write '" + path.string() +
                     "': normals were not rendered (set RenderOptions::normals)");
  }
  checkFrameBuffer(frame, frame.normal.size(), "normal");
  checkFrameBuffer(frame, frame.triangle_id.size(), "triangle_id");
  return writeAtomically(path, [&](AtomicFile& file) {
    return encodePng(file, frame.width, frame.height, kRgb8, [&](int y, uint8_t* row) {
      const size_t first = static_cast<size_t>(y) * frame.width;
      for (int x = 0; x < frame.width; ++x) {
        const float3& n = frame.normal[first + x];
        const bool drawn = frame.triangle_id[first + x] != kNoTriangle;
        row[3 * x + 0] = drawn ? unitToByte(n.x * 0.5f + 0.5f) : 0;
        row[3 * x + 1] = drawn ? unitToByte(n.y * 0.5f + 0.5f) : 0;
        row[3 * x + 2] = drawn ? unitToByte(n.z * 0.5f + 0.5f) : 0;
      }
    });
  });
}

Expected<void> writeCoveragePng(const std::filesystem::path& path, const Frame& frame) {
  if (frame.coverage.empty()) {
    return makeError("cannot write '" + path.string() +
                     "': coverage was not rendered (set RenderOptions::coverage)");
  }
  checkFrameBuffer(frame, frame.coverage.size(), "coverage");
  return writeAtomically(path, [&](AtomicFile& file) {
    return encodePng(file, frame.width, frame.height, kGray8, [&](int y, uint8_t* row) {
      std::memcpy(row, frame.coverage.data() + static_cast<size_t>(y) * frame.width,
                  static_cast<size_t>(frame.width));
    });
  });
}

}  // namespace tessera::io
