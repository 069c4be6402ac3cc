// What every model loader shares about files: reading the model file itself within a size limit,
// and resolving the files a model refers to (MTL libraries, textures, glTF buffers) to paths
// beneath the model's own folder. Private to tessera_io.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include <tessera/base/expected.h>

namespace tessera::io {

// `text` without leading and trailing blanks and line ends.
std::string trimmed(std::string_view text);

bool equalsIgnoreCase(std::string_view a, std::string_view b);

// Checks that `path` is a regular, non-empty file of at most `max_bytes` and returns its size.
// `format` names the kind of file in the message ("OBJ", "STL").
Expected<uintmax_t> checkModelFile(const std::filesystem::path& path, uintmax_t max_bytes,
                                   const std::string& format);

// The whole file, after checkModelFile's checks.
Expected<std::vector<unsigned char>> readModelFile(const std::filesystem::path& path,
                                                   uintmax_t max_bytes, const std::string& format);

// Resolves a file named inside a model (an MTL library, a texture, a buffer) to a path beneath
// `folder`, or says why it is refused: URIs, absolute paths, `..` that climbs out of the folder
// (after normalizing) and symbolic links that lead outside. '\' is taken as a separator, since
// Windows exporters write `.\tex\a.png`.
Expected<std::filesystem::path> resolveReferencedFile(const std::filesystem::path& folder,
                                                      std::string_view reference);

}  // namespace tessera::io
