// OBJ material libraries: MTL files read from beneath the OBJ's folder only (tinyobjloader never
// opens a path itself), their materials turned into tessera's, and tinyobjloader's warnings in
// tessera's words. Private to tessera_io; split from obj_loader.cpp.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include <tessera/io/model_loader.h>

#include "load_budget.h"

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-parameter"
#pragma GCC diagnostic ignored "-Wpedantic"
#include <tiny_obj_loader.h>
#pragma GCC diagnostic pop

namespace tessera::io {

// Passes tinyobjloader's warnings on, except those this loader reports better itself.
void forwardLibraryWarnings(const std::string& file, const std::string& text,
                            std::vector<std::string>& warnings);

// Reads the MTL libraries the OBJ names, from beneath the OBJ's folder only, so tinyobjloader
// never opens a path itself. tinyobjloader passes names after its own splitting, which treats
// '\' as an escape and so mangles Windows paths, and it stops at the first library of an
// `mtllib` line that loads. So the first call loads every library of every `mtllib` line from
// the text as written (found by the line index) and later calls add nothing. A `usemtl` can then
// also find a material from a library named further down the file.
class FolderMaterialReader : public tinyobj::MaterialReader {
 public:
  FolderMaterialReader(std::filesystem::path folder, std::string obj_name,
                       const std::vector<std::string>& libraries,
                       std::vector<std::string>& warnings)
      : folder_(std::move(folder)),
        obj_name_(std::move(obj_name)),
        libraries_(libraries),
        warnings_(warnings) {}

  // Per library material (tinyobjloader's numbering): whether its MTL block set Kd.
  bool hasKd(size_t material) const { return material < has_kd_.size() && has_kd_[material]; }

  bool operator()(const std::string& tinyobj_name, std::vector<tinyobj::material_t>* materials,
                  std::map<std::string, int>* material_map, std::string* warn,
                  std::string* err) override;

 private:
  std::vector<std::string> libraryNames(const std::string& text) const;
  void load(const std::string& name, std::vector<tinyobj::material_t>* materials,
            std::map<std::string, int>* material_map, std::set<std::filesystem::path>& seen);

  std::filesystem::path folder_;
  std::string obj_name_;
  const std::vector<std::string>& libraries_;
  std::vector<std::string>& warnings_;
  std::vector<char> has_kd_;
  bool done_ = false;
};

// Turns MTL materials into tessera materials, loading each texture once.
class MaterialBuilder {
 public:
  MaterialBuilder(std::filesystem::path folder, std::string obj_name,
                  std::vector<std::string>& warnings, const LoadBudget& budget)
      : folder_(std::move(folder)),
        obj_name_(std::move(obj_name)),
        warnings_(warnings),
        textures_(budget) {}

  // A texture over the budget: the model cannot be loaded.
  const std::optional<Error>& fatal() const { return fatal_; }

  Material build(const tinyobj::material_t& source, bool has_kd);

 private:
  void buildPbr(const tinyobj::material_t& source, Material& material);
  std::shared_ptr<const Texture> texture(const std::string& reference, bool srgb,
                                         const std::string& material_name);

  std::filesystem::path folder_;
  std::string obj_name_;
  std::vector<std::string>& warnings_;
  std::map<std::pair<std::string, bool>, std::shared_ptr<const Texture>> cache_;
  TextureBudget textures_;
  std::optional<Error> fatal_;
};

}  // namespace tessera::io
