// OBJ points and lines: `p` elements, `l` polylines and, in a file with no `f`, `p` or `l` lines,
// every vertex, into Model::points and Model::lines. Private to tessera_io.
#pragma once

#include <string>
#include <vector>

#include <tessera/io/model_loader.h>

#include "obj_materials.h"
#include "obj_scan.h"

namespace tessera::io {

// Whether the file has `f` lines, even ones of fewer than 3 corners (which are dropped): a file
// meant to have faces is not read as a point cloud.
bool hasFaceLines(const ObjLineIndex& lines);

// How many points and line end points the OBJ will give, for the budget: its elements' vertices,
// or every position when it has no `f` lines and no elements.
uint64_t objPointBudgetCount(const ObjLineIndex& lines);

// Appends the file's points and segments to `model` (OBJ has no transforms: world space is the
// file's). Point colours are the `v x y z r g b` colours, read as sRGB (as the point-cloud tools
// that write them, MeshLab, CloudCompare and Open3D, mean them: 8-bit colours / 255) and decoded to
// linear; a segment takes its `usemtl` material's Kd (linear, as for faces) or the default
// material's 0.8 grey. An index past the positions is an error naming the line; points and
// segments at a non-finite position are dropped with a warning.
Expected<void> addObjPointsAndLines(const std::string& name, const tinyobj::attrib_t& attrib,
                                    const ObjLineIndex& lines,
                                    const std::vector<tinyobj::material_t>& library_materials,
                                    const FolderMaterialReader& reader, Model& model);

}  // namespace tessera::io
