// The loader sandbox for assimp (model_loader.h, loadAssimp): the only way assimp opens a file.
// Private to tessera_io; built only with assimp (TESSERA_HAS_ASSIMP).
#pragma once

#include <cstdint>
#include <filesystem>
#include <map>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include <assimp/IOSystem.hpp>

namespace tessera::io {

// Serves assimp the model file and regular files beneath the model's folder, read whole (once
// each, however often assimp opens them) and counted against a byte budget; refuses anything
// else, and writing. The model may also be given as bytes in memory, with no folder: then it is
// the only file there is.
class SandboxIOSystem : public Assimp::IOSystem {
 public:
  // `model` is the name assimp is given for the model, whose bytes the caller has read (and
  // counts in `max_bytes`); the files it refers to are looked up beneath `folder`, or refused
  // when `folder` is empty (a model from memory).
  SandboxIOSystem(std::string model, std::vector<uint8_t> bytes, std::filesystem::path folder,
                  uint64_t max_bytes);

  bool Exists(const char* file) const override;
  char getOsSeparator() const override { return '/'; }
  Assimp::IOStream* Open(const char* file, const char* mode = "rb") override;
  void Close(Assimp::IOStream* stream) override;
  // assimp's default would compare the names as given; two names of one file are one file here.
  bool ComparePaths(const char* one, const char* second) const override;

  // Why files were refused (one line each, first ones only), for the loader's error and warnings.
  const std::vector<std::string>& refusals() const { return refusals_; }
  // The first refusal that was over the byte budget, or empty.
  const std::string& overBudget() const { return over_budget_; }
  uint64_t bytesRead() const { return bytes_read_; }

 private:
  using Bytes = std::shared_ptr<const std::vector<uint8_t>>;
  // The file's bytes, read on first use; null with a refusal noted when it cannot be served.
  Bytes load(const std::string& file);
  // Where `file` (as assimp names it) lives beneath the folder, or empty with `why` set.
  std::filesystem::path resolve(const std::string& file, std::string& why) const;
  void refuse(const std::string& file, const std::string& why);

  std::string model_name_;
  std::filesystem::path folder_;  // empty: the model is in memory and is the only file
  uint64_t max_bytes_;
  uint64_t bytes_read_ = 0;
  std::map<std::string, Bytes> files_;  // by resolved path
  std::vector<std::string> refusals_;
  std::string over_budget_;
};

}  // namespace tessera::io
