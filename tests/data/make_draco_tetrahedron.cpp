// Writes tests/data/draco_tetrahedron.glb (and fuzz/corpus/gltf/draco.glb, the same file): a
// tetrahedron's positions as a Draco stream (libdraco's encoder, 8-bit quantization) in a GLB
// whose accessors have no bufferView and which requires KHR_draco_mesh_compression. Not part of
// the build; the file is committed. Run it again when the model changes:
//   g++ -std=c++17 tests/data/make_draco_tetrahedron.cpp -ldraco -o /tmp/make_draco && \
//     /tmp/make_draco tests/data/draco_tetrahedron.glb
#include <draco/compression/decode.h>
#include <draco/compression/encode.h>
#include <draco/mesh/triangle_soup_mesh_builder.h>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>
int main(int argc, char** argv) {
  const float p[4][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  const int f[4][3] = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  draco::TriangleSoupMeshBuilder b;
  b.Start(4);
  int pos = b.AddAttribute(draco::GeometryAttribute::POSITION, 3, draco::DT_FLOAT32);
  for (int i = 0; i < 4; ++i)
    b.SetAttributeValuesForFace(pos, draco::FaceIndex(i), p[f[i][0]], p[f[i][1]], p[f[i][2]]);
  auto mesh = b.Finalize();
  draco::Encoder e;
  e.SetAttributeQuantization(draco::GeometryAttribute::POSITION, 8);
  draco::EncoderBuffer out;
  if (!e.EncodeMeshToBuffer(*mesh, &out).ok()) return 1;
  draco::DecoderBuffer in;
  in.Init(out.data(), out.size());
  draco::Decoder d;
  auto m = d.DecodeMeshFromBuffer(&in);
  unsigned points = m.value()->num_points(), faces = m.value()->num_faces();
  std::vector<char> bin(out.data(), out.data() + out.size());
  while (bin.size() % 4) bin.push_back(0);
  std::string json =
      "{\"asset\":{\"version\":\"2.0\"},\"extensionsUsed\":[\"KHR_draco_mesh_compression\"],"
      "\"extensionsRequired\":[\"KHR_draco_mesh_compression\"],\"buffers\":[{\"byteLength\":" +
      std::to_string(bin.size()) +
      "}],\"bufferViews\":[{\"buffer\":0,\"byteLength\":" + std::to_string(out.size()) +
      "}],"
      "\"accessors\":[{\"componentType\":5126,\"type\":\"VEC3\",\"count\":" +
      std::to_string(points) +
      ",\"min\":[0,0,0],\"max\":[1,1,1]},{\"componentType\":5121,\"type\":\"SCALAR\",\"count\":" +
      std::to_string(3 * faces) +
      "}],"
      "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0},\"indices\":1,\"extensions\":{"
      "\"KHR_draco_mesh_compression\":"
      "{\"bufferView\":0,\"attributes\":{\"POSITION\":" +
      std::to_string(mesh->attribute(pos)->unique_id()) +
      "}}}}]}],"
      "\"nodes\":[{\"mesh\":0}],\"scenes\":[{\"nodes\":[0]}]}";
  while (json.size() % 4) json += ' ';
  std::vector<char> glb;
  auto u32 = [&](uint32_t v) {
    char c[4];
    std::memcpy(c, &v, 4);
    glb.insert(glb.end(), c, c + 4);
  };
  u32(0x46546C67);
  u32(2);
  u32(12 + 8 + json.size() + 8 + bin.size());
  u32(json.size());
  u32(0x4E4F534A);
  glb.insert(glb.end(), json.begin(), json.end());
  u32(bin.size());
  u32(0x004E4942);
  glb.insert(glb.end(), bin.begin(), bin.end());
  FILE* file = std::fopen(argv[1], "wb");
  std::fwrite(glb.data(), 1, glb.size(), file);
  std::fclose(file);
  std::printf("%zu bytes, %u points %u faces, stream %zu\n", glb.size(), points, faces, out.size());
}
