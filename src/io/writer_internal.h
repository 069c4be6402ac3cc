// Pieces shared by the PNG writer and the frame sinks; not part of the public API.
#pragma once

#include <cstdint>

#include <tessera/base/expected.h>
#include <tessera/io/atomic_file.h>
#include <tessera/io/frame_sink.h>

namespace tessera::io {

// Encodes RGBA8 pixels as a PNG into an open AtomicFile, without closing or committing it.
Expected<void> encodePngRgba8(AtomicFile& file, int width, int height, const uint32_t* pixels,
                              bool keep_alpha);

// Rejects sizes and rates the sinks cannot honour, naming the offending setting.
Expected<void> validateAnimationSettings(const AnimationSettings& settings);

}  // namespace tessera::io
