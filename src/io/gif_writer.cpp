// Animated GIF: giflib writes the stream. A frame of at most 256 colours (flat-shaded renders
// without anti-aliasing, such as the cube demo) gets exactly those colours as its palette, with
// nothing lost and no dithering; any other frame gets a 256-colour palette picked and dithered
// to by libimagequant. Frames are encoded as they are added, so memory holds one frame, not the
// film.
#include <gif_lib.h>
#include <libimagequant.h>

#include <array>
#include <cstddef>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <tessera/io/atomic_file.h>
#include <tessera/io/frame_sink.h>

#include "writer_internal.h"

namespace tessera::io {
namespace {

// Full dithering: rendered gradients band badly with 256 colours otherwise.
constexpr float kDitheringLevel = 1.0f;

const char* liqErrorString(liq_error error) {
  switch (error) {
    case LIQ_OK:
      return "no error";
    case LIQ_QUALITY_TOO_LOW:
      return "quality too low";
    case LIQ_VALUE_OUT_OF_RANGE:
      return "value out of range";
    case LIQ_OUT_OF_MEMORY:
      return "out of memory";
    case LIQ_ABORTED:
      return "aborted";
    case LIQ_BITMAP_NOT_AVAILABLE:
      return "bitmap not available";
    case LIQ_BUFFER_TOO_SMALL:
      return "buffer too small";
    case LIQ_INVALID_POINTER:
      return "invalid pointer";
    case LIQ_UNSUPPORTED:
      return "unsupported";
  }
  return "unknown error";
}

struct LiqImageDeleter {
  void operator()(liq_image* image) const { liq_image_destroy(image); }
};
struct LiqResultDeleter {
  void operator()(liq_result* result) const { liq_result_destroy(result); }
};
struct GifColorMapDeleter {
  void operator()(ColorMapObject* map) const { GifFreeMapObject(map); }
};

struct FramePixels {
  const uint32_t* pixels;
  int width;
};

// Hands libimagequant one row at a time, opaque: a GIF frame has no partial alpha, and the
// renderer's alpha is coverage, not transparency the animation should show.
void fetchRow(liq_color row_out[], int row, int width, void* user_info) {
  const auto* frame = static_cast<const FramePixels*>(user_info);
  const uint32_t* in = frame->pixels + static_cast<size_t>(row) * frame->width;
  for (int x = 0; x < width; ++x) {
    row_out[x].r = static_cast<unsigned char>(in[x]);
    row_out[x].g = static_cast<unsigned char>(in[x] >> 8);
    row_out[x].b = static_cast<unsigned char>(in[x] >> 16);
    row_out[x].a = 255;
  }
}

// The frame's exact palette when it has at most 256 colours (RGB; alpha is dropped as in
// fetchRow): each pixel's index into `colours` in `indices`, colours in order of first
// appearance, and their count; 0 when the frame has more colours than that. An open-addressing
// table of 1024 slots keyed by colour, and the previous pixel's colour remembered, since runs are
// the common case: about a millisecond for a 480x480 frame, against tens for quantizing.
int exactPalette(const uint32_t* pixels, size_t count, uint8_t* indices,
                 std::array<GifColorType, 256>& colours) {
  constexpr uint32_t kSlots = 1024;  // a power of two, at most a quarter full
  constexpr uint32_t kEmpty = 0xffffffffu;
  std::array<uint32_t, kSlots> keys;
  std::array<uint8_t, kSlots> slot_index{};
  keys.fill(kEmpty);
  int used = 0;
  uint32_t last_rgb = kEmpty;
  uint8_t last_index = 0;
  for (size_t i = 0; i < count; ++i) {
    const uint32_t rgb = pixels[i] & 0xffffffu;
    if (rgb != last_rgb) {
      uint32_t slot = (rgb * 0x9e3779b1u) >> 22;  // Fibonacci hashing to 10 bits
      while (keys[slot] != kEmpty && keys[slot] != rgb) slot = (slot + 1) & (kSlots - 1);
      if (keys[slot] == kEmpty) {
        if (used == 256) return 0;
        keys[slot] = rgb;
        slot_index[slot] = static_cast<uint8_t>(used);
        colours[static_cast<size_t>(used)] = {static_cast<GifByteType>(rgb),
                                              static_cast<GifByteType>(rgb >> 8),
                                              static_cast<GifByteType>(rgb >> 16)};
        ++used;
      }
      last_rgb = rgb;
      last_index = slot_index[slot];
    }
    indices[i] = last_index;
  }
  return used;
}

class GifSink : public FrameSink {
 public:
  static Expected<std::unique_ptr<FrameSink>> open(const std::filesystem::path& path,
                                                   const AnimationSettings& settings);
  ~GifSink() override;
  Expected<void> addFrame(const uint32_t* pixels) override;
  Expected<void> finish() override;

 private:
  GifSink(AtomicFile file, const AnimationSettings& settings)
      : file_(std::move(file)),
        settings_(settings),
        indices_(static_cast<size_t>(settings.width) * settings.height) {}
  Expected<void> start();
  Expected<void> putLoopExtension();
  Expected<void> encodeFrame(const uint32_t* pixels);
  Expected<int> quantizeFrame(const uint32_t* pixels, std::array<GifColorType, 256>& colours);
  Error gifFailure(const char* step, int code);
  static int writeBytes(GifFileType* gif, const GifByteType* data, int length);

  AtomicFile file_;
  AnimationSettings settings_;
  GifFileType* gif_ = nullptr;
  liq_attr* quantizer_ = nullptr;
  std::vector<uint8_t> indices_;      // palette indices of the frame being encoded
  std::optional<Error> write_error_;  // the OS reason behind a giflib write failure
  std::optional<Error> failure_;      // a half-written frame makes the rest of the stream moot
  int frame_count_ = 0;
  bool finished_ = false;
};

int GifSink::writeBytes(GifFileType* gif, const GifByteType* data, int length) {
  auto* sink = static_cast<GifSink*>(gif->UserData);
  if (sink->write_error_) return 0;
  Expected<void> written = sink->file_.write(data, static_cast<size_t>(length));
  if (!written) {
    sink->write_error_ = written.error();
    return 0;
  }
  return length;
}

Error GifSink::gifFailure(const char* step, int code) {
  if (write_error_) return *write_error_;
  const char* reason = GifErrorString(code);
  return makeError("cannot encode GIF '" + file_.target().string() + "': " + step + ": " +
                   (reason != nullptr ? reason : "unknown giflib error"));
}

Expected<std::unique_ptr<FrameSink>> GifSink::open(const std::filesystem::path& path,
                                                   const AnimationSettings& settings) {
  if (auto valid = validateAnimationSettings(settings); !valid) return valid.error();
  Expected<AtomicFile> file = AtomicFile::create(path);
  if (!file) return file.error();
  // Built in place and never moved: giflib keeps a pointer to it for the write callback.
  std::unique_ptr<GifSink> sink(new GifSink(std::move(*file), settings));
  if (auto started = sink->start(); !started) return started.error();
  return std::unique_ptr<FrameSink>(std::move(sink));
}

Expected<void> GifSink::start() {
  int error = 0;
  gif_ = EGifOpen(this, &GifSink::writeBytes, &error);
  if (gif_ == nullptr) return gifFailure("open", error);
  // GIF89a: the loop and frame delay extensions do not exist in GIF87a.
  EGifSetGifVersion(gif_, true);
  // No global palette: every frame brings its own.
  if (EGifPutScreenDesc(gif_, settings_.width, settings_.height, 8, 0, nullptr) == GIF_ERROR) {
    return gifFailure("screen descriptor", gif_->Error);
  }
  if (settings_.loop) {
    if (auto looped = putLoopExtension(); !looped) return looped;
  }
  quantizer_ = liq_attr_create();
  if (quantizer_ == nullptr) return makeError("cannot create the GIF palette quantizer");
  if (liq_error error = liq_set_max_colors(quantizer_, 256); error != LIQ_OK) {
    return makeError(std::string("cannot set up the GIF palette quantizer: ") +
                     liqErrorString(error));
  }
  return {};
}

// The NETSCAPE2.0 application extension, which every GIF viewer reads as "repeat"; a loop count
// of 0 means forever.
Expected<void> GifSink::putLoopExtension() {
  static constexpr char kApplication[] = "NETSCAPE2.0";
  static constexpr GifByteType kLoopForever[] = {1, 0, 0};  // sub-block 1, count 0 little-endian
  if (EGifPutExtensionLeader(gif_, APPLICATION_EXT_FUNC_CODE) == GIF_ERROR ||
      EGifPutExtensionBlock(gif_, sizeof(kApplication) - 1, kApplication) == GIF_ERROR ||
      EGifPutExtensionBlock(gif_, sizeof(kLoopForever), kLoopForever) == GIF_ERROR ||
      EGifPutExtensionTrailer(gif_) == GIF_ERROR) {
    return gifFailure("loop extension", gif_->Error);
  }
  return {};
}

GifSink::~GifSink() {
  // Closing writes the trailer into the temporary file, which file_ then removes.
  if (gif_ != nullptr) EGifCloseFile(gif_, nullptr);
  if (quantizer_ != nullptr) liq_attr_destroy(quantizer_);
}

Expected<void> GifSink::addFrame(const uint32_t* pixels) {
  TESSERA_CHECK(!finished_) << "addFrame() after finish() for " << file_.target();
  TESSERA_CHECK(pixels != nullptr) << "no pixels for frame " << frame_count_;
  if (failure_) return *failure_;
  Expected<void> encoded = encodeFrame(pixels);
  if (!encoded) failure_ = encoded.error();
  return encoded;
}

// libimagequant's palette for the frame, dithered into indices_; returns the palette's size.
Expected<int> GifSink::quantizeFrame(const uint32_t* pixels,
                                     std::array<GifColorType, 256>& colours) {
  auto quantizeFailure = [&](liq_error error) {
    return makeError("cannot make the palette of frame " + std::to_string(frame_count_) + " of '" +
                     file_.target().string() + "': " + liqErrorString(error));
  };
  FramePixels frame{pixels, settings_.width};
  std::unique_ptr<liq_image, LiqImageDeleter> image(liq_image_create_custom(
      quantizer_, fetchRow, &frame, settings_.width, settings_.height, 0.0));
  if (!image) return quantizeFailure(LIQ_OUT_OF_MEMORY);
  liq_result* raw_result = nullptr;
  if (liq_error error = liq_image_quantize(image.get(), quantizer_, &raw_result); error != LIQ_OK) {
    return quantizeFailure(error);
  }
  std::unique_ptr<liq_result, LiqResultDeleter> result(raw_result);
  if (liq_error error = liq_set_dithering_level(result.get(), kDitheringLevel); error != LIQ_OK) {
    return quantizeFailure(error);
  }
  if (liq_error error =
          liq_write_remapped_image(result.get(), image.get(), indices_.data(), indices_.size());
      error != LIQ_OK) {
    return quantizeFailure(error);
  }
  const liq_palette* palette = liq_get_palette(result.get());
  for (unsigned i = 0; i < palette->count; ++i) {
    colours[i] = {palette->entries[i].r, palette->entries[i].g, palette->entries[i].b};
  }
  return static_cast<int>(palette->count);
}

Expected<void> GifSink::encodeFrame(const uint32_t* pixels) {
  const int width = settings_.width;
  const int height = settings_.height;
  // A GIF palette has a power-of-two size; the unused tail stays black.
  std::array<GifColorType, 256> colours{};
  int colour_count = exactPalette(pixels, indices_.size(), indices_.data(), colours);
  if (colour_count == 0) {
    Expected<int> quantized = quantizeFrame(pixels, colours);
    if (!quantized) return quantized.error();
    colour_count = *quantized;
  }
  const int palette_size = 1 << GifBitSize(colour_count);
  std::unique_ptr<ColorMapObject, GifColorMapDeleter> colour_map(
      GifMakeMapObject(palette_size, colours.data()));
  if (!colour_map) return gifFailure("palette", E_GIF_ERR_NOT_ENOUGH_MEM);

  GraphicsControlBlock control{};
  control.DisposalMode = DISPOSE_DO_NOT;  // every frame covers the whole screen
  control.UserInputFlag = false;
  control.DelayTime = gifFrameDelayCs(frame_count_, settings_.fps);
  control.TransparentColor = NO_TRANSPARENT_COLOR;
  GifByteType control_bytes[4];
  const size_t control_size = EGifGCBToExtension(&control, control_bytes);
  if (EGifPutExtension(gif_, GRAPHICS_EXT_FUNC_CODE, static_cast<int>(control_size),
                       control_bytes) == GIF_ERROR) {
    return gifFailure("frame delay", gif_->Error);
  }
  if (EGifPutImageDesc(gif_, 0, 0, width, height, false, colour_map.get()) == GIF_ERROR) {
    return gifFailure("image descriptor", gif_->Error);
  }
  for (int y = 0; y < height; ++y) {
    if (EGifPutLine(gif_, indices_.data() + static_cast<size_t>(y) * width, width) == GIF_ERROR) {
      return gifFailure("pixels", gif_->Error);
    }
  }
  ++frame_count_;
  return {};
}

Expected<void> GifSink::finish() {
  TESSERA_CHECK(!finished_) << "finish() called twice for " << file_.target();
  finished_ = true;
  if (failure_) return *failure_;
  if (frame_count_ == 0) {
    return makeError("no frames were rendered for '" + file_.target().string() + "'");
  }
  int error = 0;
  // EGifCloseFile frees the handle whatever happens, and does not check its own last write:
  // write_error_ does.
  const int closed = EGifCloseFile(std::exchange(gif_, nullptr), &error);
  if (write_error_) return *write_error_;
  if (closed == GIF_ERROR) return gifFailure("close", error);
  return file_.commit();
}

}  // namespace

Expected<std::unique_ptr<FrameSink>> openGifSink(const std::filesystem::path& path,
                                                 const AnimationSettings& settings) {
  return GifSink::open(path, settings);
}

}  // namespace tessera::io
