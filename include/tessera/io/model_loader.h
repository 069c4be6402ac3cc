// Model loaders. Every file is treated as hostile: a malformed, truncated or huge file ends in
// one Error naming the file (and line for text formats); never a crash, hang or unbounded
// allocation.
#pragma once

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <tessera/base/expected.h>
#include <tessera/scene/graph.h>
#include <tessera/scene/scene.h>

namespace tessera::io {

// What a model may cost, checked before anything is allocated for it: every limit derives from
// one memory limit unless given itself. Over budget is an error naming the budget and the flag
// that raises it (`tessera render --memory-limit`, `--max-triangles`, `--max-texture-pixels`).
struct LoadBudget {
  static constexpr uint64_t kDefaultMemoryBytes = uint64_t{1} << 30;

  uint64_t memory_bytes = kDefaultMemoryBytes;  // --memory-limit
  uint64_t max_triangles = 0;                   // --max-triangles; 0: memory_bytes / 512
  uint64_t max_texture_pixels = 0;  // --max-texture-pixels, per texture; 0: memory_bytes / 16

  // Triangles drawn, after glTF instancing: loading and rendering take about 400 bytes each
  // (the mesh, the renderer's clipped and set-up triangles and its bins), so 2,097,152 for 1 GiB.
  uint64_t triangles() const { return max_triangles ? max_triangles : memory_bytes / 512; }
  // Mesh vertices (positions, normals, uvs, colours and the renderer's transformed copies).
  uint64_t vertices() const { return std::max(triangles(), memory_bytes / 256); }
  // Points and line end points (Model::points, Model::lines): about 64 bytes each (position and
  // colour in the model and again in the loader's reading of the file, the point pass's
  // transformed copy), so 16,777,216 for 1 GiB. Only --memory-limit raises it.
  uint64_t points() const { return memory_bytes / 64; }
  // Decoded pixels of one texture (4 bytes each, a third more for mipmaps, twice that while
  // decoding): 8192 x 8192 for 1 GiB.
  uint64_t texturePixels() const {
    return max_texture_pixels ? max_texture_pixels : memory_bytes / 16;
  }
  // Decoded pixels of all of a model's textures together.
  uint64_t totalTexturePixels() const { return std::max(texturePixels(), memory_bytes / 12); }
  // Bytes of the model's files (the model, MTL libraries, glTF buffers and images) read.
  uint64_t fileBytes() const { return memory_bytes; }
};

struct Model {
  // OBJ, STL and models built by hand: one mesh, the scene's one node (takeGraph).
  Mesh mesh;                        // triangles in the contract's load order
  std::vector<Material> materials;  // at least one; Mesh::triangle_materials indexes these
  // glTF: the scene graph (graph.h), each mesh stored once and drawn by every node that refers
  // to it; `mesh` is then empty and `materials` lists the file's materials, the list every graph
  // mesh shares (GraphMesh::materials). The instances' triangles, depth-first over the
  // nodes, are the contract's load order (flattenedMesh).
  SceneGraph graph;
  std::vector<std::string> warnings;  // things skipped or replaced (missing MTL, NaN vertices...)
  size_t nonfinite_triangles = 0;     // triangles with a NaN or infinite vertex (kept in the list
                                      // so ids stay in load order; the renderer drops them)
  // Whether the file asks for back faces to be culled, for formats that say (glTF materials'
  // `doubleSided`); empty for OBJ and STL, which leave it to the user. The renderer culls per
  // Object, materials say it per triangle, so this is the one setting that drops nothing meant
  // to be seen: true when no material in use is double-sided, false when any is (a warning says
  // when they are mixed). A caller (`tessera render` without --backface-type) uses
  // CullMode::kBack when it is true, CullMode::kNone when it is false, and its own default when
  // it is empty. Material::double_sided keeps the per-material answer.
  std::optional<bool> cull_back_faces;
  // glTF KHR_lights_punctual: the file's lights in world space (gltf_lights.cpp), in node order;
  // empty for other formats. A caller lights the model with these instead of its default rig.
  std::vector<Light> lights;
  // Primitives without faces, in world space (node transforms applied at load): OBJ `p` and `l`
  // elements and an OBJ without faces, glTF POINTS and LINES modes, assimp's point and line
  // faces and a PLY of vertices only. A model may hold only these (no triangles);
  // model::makeModelScene moves them into Scene::points and Scene::lines. Colours are linear
  // RGB. A loader with nothing at all to draw fails: "nothing to draw: no faces, points or lines".
  PointList points;
  LineList lines;
};

// The model's scene graph, moved out of it: `graph` when the loader built one, else one node
// drawing `mesh` with `materials` (world = identity). World matrices are up to date.
SceneGraph takeGraph(Model&& model);

// Every triangle drawn, in world space and in id order: `mesh` itself, or the graph's instances
// flattened (SceneGraph::flatten). For tools and tests; a renderer instances the graph.
Mesh flattenedMesh(const Model& model);

// By extension (case-insensitive): .obj, .gltf, .glb and .stl with tessera's own loaders, every
// other extension assimp reads (modelFormats) through loadAssimp.
Expected<Model> loadModel(const std::filesystem::path& path, const LoadBudget& budget = {});

// Wavefront OBJ with its MTL files (tinyobjloader). Faces in file order; convex polygons are
// fan-split from their first vertex, concave ones ear-clipped. Missing normals are generated
// (smooth, area-weighted). Materials are listed in the order triangles first use them; faces
// without one get a default Material (0.8 grey). MTL files and textures are read only from
// beneath the OBJ's folder; anything else is skipped with a warning. `p` elements are points and
// `l` polylines line segments (consecutive pairs), in Model::points and Model::lines; a file
// without any `f`, `p` or `l` line is a point cloud of its vertices. Point colours are the `v`
// line's colour read as sRGB (point-cloud tools write 8-bit colours / 255) and decoded; a
// segment takes its `usemtl` material's Kd or the default 0.8 grey (obj_points.h).
Expected<Model> loadObj(const std::filesystem::path& path, const LoadBudget& budget = {});

// glTF 2.0, as JSON (.gltf) or binary (.glb; chosen by the file's magic, not its name), through
// tinygltf. The default scene (else scene 0, else every root node) becomes Model::graph: its
// nodes depth-first from each root in order (a node before its children), each with its local
// transform, name, mesh and camera; each glTF mesh is read once, in its own space, all its
// primitives in order into one Mesh, triangles in index order, and drawn by every node that
// refers to it. Triangle ids run over the instances in node order. An instance whose world matrix
// mirrors (determinant < 0) is drawn with its winding reversed so front faces stay front
// (SceneGraph::prepareMeshes). Cameras (perspective and orthographic) go to graph.cameras; a
// camera with a zero or negative field is skipped with a warning naming it (and keeps its
// index: GraphCamera::skipped). TRIANGLES, TRIANGLE_STRIP and
// TRIANGLE_FAN are drawn as meshes; POINTS, LINES, LINE_LOOP and LINE_STRIP go, at the world
// matrix of every node that draws their mesh, into Model::points and Model::lines, coloured
// baseColorFactor x COLOR_0 (gltf_points.cpp). Materials (first-use
// order) take baseColorFactor, the baseColorTexture (sRGB) with its sampler, and doubleSided;
// texture coordinates have v flipped to tessera's convention (v = 0 at the bottom). COLOR_0 is a
// linear vertex colour. Missing normals are generated (smooth, area-weighted). Sparse accessors
// are supported. Buffers and images come from `data:` URIs, the GLB binary chunk, or files
// beneath the model's folder; nothing else is opened.
Expected<Model> loadGltf(const std::filesystem::path& path, const LoadBudget& budget = {});

// The same from bytes in memory. `name` is used in messages; external buffers and images are
// looked up beneath `folder`, or refused when `folder` is empty.
Expected<Model> loadGltfFromMemory(std::span<const uint8_t> bytes, const std::string& name,
                                   const std::filesystem::path& folder = {},
                                   const LoadBudget& budget = {});

// STL, binary or ASCII. Binary when the size is exactly 84 + 50 * the facet count in the header
// (so a binary file whose header starts with "solid" is still binary), ASCII when the text
// starts with "solid". Triangles are the facets in file order; identical positions are welded
// and smooth normals generated (the facet normals are ignored). One default material.
Expected<Model> loadStl(const std::filesystem::path& path, const LoadBudget& budget = {});

// The same from bytes in memory; `name` is used in messages.
Expected<Model> loadStlFromMemory(std::span<const uint8_t> bytes, const std::string& name,
                                  const LoadBudget& budget = {});

// A format tessera reads: its name, its extensions (lower case, without the dot) and which
// reader reads it ("tessera" or "assimp").
struct ModelFormat {
  std::string name;
  std::vector<std::string> extensions;
  std::string reader;
};

// Every format loadModel reads: tessera's own first (OBJ, glTF, STL), then assimp's in its
// order, without the extensions tessera's loaders keep. Empty for assimp when the build has none.
std::vector<ModelFormat> modelFormats();

// Whether this build reads the formats through assimp (TESSERA_ASSIMP and libassimp-dev).
bool hasAssimp();

// Any format assimp reads (PLY, OFF, COLLADA, FBX, 3DS, 3MF...), through assimp, sandboxed: the
// file's size is checked first, then PLY headers and OFF files; assimp reads the file first in a
// child process (memory capped, time limited: a crash or hang there is an error, not tessera's
// end), and only then in this one; assimp opens files only through an IO system that serves
// regular files beneath the model's folder within LoadBudget::fileBytes() (never a FIFO, device,
// absolute or climbing path); the scene's triangle and vertex counts are checked against the
// budget before anything is copied; its failures and exceptions become one error naming the
// file ("NAME: assimp cannot read it: REASON"). Triangulated, identical vertices joined. The node
// hierarchy becomes Model::graph (each assimp mesh list stored once, drawn by every node that
// refers to it; triangle ids depth-first over the nodes as for glTF). Normals when the file has
// them (else smooth ones are generated), UV set 0, vertex colour set 0 (sRGB-encoded in every
// format assimp reads, decoded to linear), materials with their diffuse colour, opacity,
// two-sidedness and diffuse texture (embedded, or a file beneath the model's folder). Point and
// line faces, and meshes of vertices without faces (a PLY of vertices only), go into
// Model::points and Model::lines at every node that draws them (assimp_points.cpp); a faceless
// PLY's vertex count is checked against LoadBudget::points() from its header. Without assimp in
// the build, an error says so.
Expected<Model> loadAssimp(const std::filesystem::path& path, const LoadBudget& budget = {});

// The same from bytes in memory: `name`'s extension picks the format (assimp also looks at the
// bytes); nothing but these bytes can be opened (textures are refused with a warning).
Expected<Model> loadAssimpFromMemory(std::span<const uint8_t> bytes, const std::string& name,
                                     const LoadBudget& budget = {});

}  // namespace tessera::io
