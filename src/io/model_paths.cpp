#include "model_paths.h"

#include <algorithm>
#include <cctype>
#include <fstream>
#include <string>
#include <system_error>

namespace tessera::io {

namespace fs = std::filesystem;

std::string trimmed(std::string_view text) {
  const char* kSpace = " \t\r\n";
  size_t begin = text.find_first_not_of(kSpace);
  if (begin == std::string_view::npos) return {};
  size_t end = text.find_last_not_of(kSpace);
  return std::string(text.substr(begin, end - begin + 1));
}

bool equalsIgnoreCase(std::string_view a, std::string_view b) {
  return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin(), [](char x, char y) {
           return std::tolower(static_cast<unsigned char>(x)) ==
                  std::tolower(static_cast<unsigned char>(y));
         });
}

namespace {

// "2 GiB", "64 MiB" or a byte count.
std::string sizeText(uintmax_t bytes) {
  if (bytes >= (uintmax_t{1} << 30) && bytes % (uintmax_t{1} << 30) == 0)
    return std::to_string(bytes >> 30) + " GiB";
  if (bytes >= (uintmax_t{1} << 20) && bytes % (uintmax_t{1} << 20) == 0)
    return std::to_string(bytes >> 20) + " MiB";
  return std::to_string(bytes) + " bytes";
}

}  // namespace

Expected<uintmax_t> checkModelFile(const fs::path& path, uintmax_t max_bytes,
                                   const std::string& format) {
  const std::string name = path.string();
  std::error_code error;
  fs::file_status status = fs::status(path, error);
  if (error || !fs::exists(status)) return makeError(name + ": no such file");
  if (!fs::is_regular_file(status)) return makeError(name + ": not a regular file");
  const uintmax_t size = fs::file_size(path, error);
  if (error) return makeError(name + ": cannot read the file size: " + error.message());
  if (size > max_bytes)
    return makeError(name + ": the file is " + std::to_string(size) + " bytes; " + format +
                     " files over " + sizeText(max_bytes) + " are refused");
  if (size == 0) return makeError(name + ": the file is empty: no triangles");
  return size;
}

Expected<std::vector<unsigned char>> readModelFile(const fs::path& path, uintmax_t max_bytes,
                                                   const std::string& format) {
  Expected<uintmax_t> size = checkModelFile(path, max_bytes, format);
  if (!size) return size.error();
  std::ifstream in(path, std::ios::binary);
  if (!in) return makeError(path.string() + ": cannot open the file");
  std::vector<unsigned char> bytes(static_cast<size_t>(*size));
  in.read(reinterpret_cast<char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
  // A file that shrank while being read is read as far as it goes.
  bytes.resize(static_cast<size_t>(in.gcount()));
  if (in.bad()) return makeError(path.string() + ": read error");
  if (bytes.empty()) return makeError(path.string() + ": the file is empty: no triangles");
  return bytes;
}

Expected<fs::path> resolveReferencedFile(const fs::path& folder, std::string_view reference) {
  std::string name = trimmed(reference);
  if (name.empty()) return makeError("the file name is empty");
  // A scheme (http:, file:, data:) or a drive letter (C:) ahead of any separator.
  size_t scheme_end = 0;
  while (scheme_end < name.size()) {
    unsigned char c = static_cast<unsigned char>(name[scheme_end]);
    if (!std::isalnum(c) && c != '+' && c != '-' && c != '.') break;
    ++scheme_end;
  }
  if (scheme_end > 0 && scheme_end < name.size() && name[scheme_end] == ':' &&
      std::isalpha(static_cast<unsigned char>(name[0]))) {
    if (scheme_end == 1) return makeError("it is an absolute path");
    return makeError("it is a URI; only files beneath the model's folder are read");
  }
  std::replace(name.begin(), name.end(), '\\', '/');
  if (name.front() == '/') return makeError("it is an absolute path");

  std::vector<std::string> parts;
  size_t begin = 0;
  while (begin <= name.size()) {
    size_t end = std::min(name.find('/', begin), name.size());
    std::string part = name.substr(begin, end - begin);
    begin = end + 1;
    if (part.empty() || part == ".") continue;
    if (part == "..") {
      if (parts.empty()) return makeError("it leads out of the model's folder");
      parts.pop_back();
      continue;
    }
    parts.push_back(std::move(part));
  }
  if (parts.empty()) return makeError("it names the model's folder, not a file");
  fs::path full = folder;
  for (const std::string& part : parts) full /= part;

  // The lexical check cannot see a symbolic link beneath the folder that points outside it.
  std::error_code error;
  if (fs::exists(full, error)) {
    std::error_code folder_error;
    fs::path real = fs::canonical(full, error);
    fs::path real_folder = fs::canonical(folder, folder_error);
    if (error || folder_error) return makeError("its location cannot be resolved");
    fs::path inside = real.lexically_relative(real_folder);
    if (inside.empty() || *inside.begin() == "..")
      return makeError("it leads out of the model's folder through a symbolic link");
  }
  return full;
}

}  // namespace tessera::io
