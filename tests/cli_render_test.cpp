// End-to-end tests of `tessera render` and `info`: AOVs, the background and framing, turntables,
// textures, cameras, and models against their reference images (the fixture: cli_test_fixture.h).
#include "cli_test_fixture.h"

namespace {
class CliRender : public Cli {};
}  // namespace

TEST_F(CliRender, RenderIdAovEncodesTriangleIndexPlusOne) {
  writeQuadObj("quad.obj");
  RunResult r =
      run("render quad.obj --resolution 40,30 --aov id -o id.png "
          "--camera-position 0,0,3 --camera-focal-point 0,0,0");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  DecodedPng png;
  ASSERT_TRUE(tessera::test::decodePng((dir_ / "id.png").string(), png));
  EXPECT_EQ(png.width, 40);
  EXPECT_EQ(png.height, 30);
  ASSERT_EQ(png.channels, 3);
  std::set<int> ids;
  for (int y = 0; y < png.height; ++y)
    for (int x = 0; x < png.width; ++x)
      ids.insert(png.at(x, y, 0) + 256 * png.at(x, y, 1) + 65536 * png.at(x, y, 2));
  // The quad is fan-split from its first vertex: triangles 1 and 2, and background 0.
  EXPECT_EQ(ids, (std::set<int>{0, 1, 2}));
  // Corner pixels are background; the centre is covered. Lower-right is triangle (1,2,3) = id 1.
  EXPECT_EQ(png.at(0, 0, 0), 0);
  EXPECT_EQ(png.at(25, 20, 0), 1);
  EXPECT_EQ(png.at(14, 10, 0), 2);
}

// A Draco-compressed GLB (KHR_draco_mesh_compression, required) rendered end to end: every face
// of the tetrahedron the camera sees has its id, in the decoder's order.
TEST_F(CliRender, RenderDracoGlbDrawsItsTriangles) {
  const std::string model = std::string(TESSERA_TEST_DATA_DIR) + "/draco_tetrahedron.glb";
  RunResult r = run("render '" + model +
                    "' --resolution 60,40 --aov id -o id.png "
                    "--camera-position 2,2,2 --camera-focal-point 0,0,0");
#if !TESSERA_HAS_DRACO
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("needs KHR_draco_mesh_compression (this build has no Draco decoder)"),
            std::string::npos)
      << r.err;
  GTEST_SKIP() << "this build has no Draco decoder: the file is refused";
#endif
  ASSERT_EQ(r.exit_code, 0) << r.err;
  DecodedPng png;
  ASSERT_TRUE(tessera::test::decodePng((dir_ / "id.png").string(), png));
  std::set<int> ids;
  for (int y = 0; y < png.height; ++y)
    for (int x = 0; x < png.width; ++x)
      ids.insert(png.at(x, y, 0) + 256 * png.at(x, y, 1) + 65536 * png.at(x, y, 2));
  // From (2,2,2) the three faces at the origin's planes are back faces of the closed
  // tetrahedron, culled; the slanted face is triangle 1, 2, 3 or 4 in the decoder's order.
  EXPECT_EQ(ids.size(), 2u);
  EXPECT_TRUE(ids.count(0));
  EXPECT_GE(*ids.rbegin(), 1);
  EXPECT_LE(*ids.rbegin(), 4);
}

TEST_F(CliRender, RenderDepthAndNormalAovs) {
  writeQuadObj("quad.obj");
  RunResult r = run("render quad.obj --resolution 40,30 --aov depth -o depth.png");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  DecodedPng depth;
  ASSERT_TRUE(tessera::test::decodePng((dir_ / "depth.png").string(), depth));
  EXPECT_EQ(depth.channels, 1);
  EXPECT_EQ(depth.bit_depth, 16);
  EXPECT_EQ(depth.at(0, 0, 0), 65535);  // nothing drawn: far
  EXPECT_LT(depth.at(20, 15, 0), 65535);
  EXPECT_GT(depth.at(20, 15, 0), 0);

  r =
      run("render quad.obj --resolution 40,30 --aov normal -o normal.png "
          "--camera-position 0,0,3 --camera-focal-point 0,0,0");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  DecodedPng normal;
  ASSERT_TRUE(tessera::test::decodePng((dir_ / "normal.png").string(), normal));
  // The quad faces +Z: normal (0, 0, 1) encodes as (128, 128, 255).
  EXPECT_NEAR(normal.at(20, 15, 0), 128, 1);
  EXPECT_NEAR(normal.at(20, 15, 1), 128, 1);
  EXPECT_EQ(normal.at(20, 15, 2), 255);
  EXPECT_EQ(normal.at(0, 0, 2), 0);
}

TEST_F(CliRender, RenderColourUsesTheBackgroundAndFramesTheModel) {
  writeQuadObj("quad.obj");
  RunResult r = run("render quad.obj --resolution 50,40 --background-color 1,0,0 --shading flat");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  DecodedPng png;
  ASSERT_TRUE(tessera::test::decodePng((dir_ / "quad.png").string(), png));  // default name
  EXPECT_EQ(png.at(0, 0, 0), 255);
  EXPECT_EQ(png.at(0, 0, 1), 0);
  // Framed: the model is in the middle and covers a good part of the image.
  int covered = 0;
  for (int y = 0; y < png.height; ++y)
    for (int x = 0; x < png.width; ++x)
      covered += !(png.at(x, y, 0) == 255 && png.at(x, y, 1) == 0);
  EXPECT_GT(covered, 50 * 40 / 6);
  EXPECT_LT(covered, 50 * 40);
  EXPECT_FALSE(png.at(25, 20, 0) == 255 && png.at(25, 20, 1) == 0);
}

TEST_F(CliRender, RenderTurntableWritesAPngSequence) {
  writeQuadObj("quad.obj");
  RunResult r = run("render quad.obj --resolution 24,24 --turntable 4 -o turn_{frame}.png");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (int i = 0; i < 4; ++i) {
    char name[32];
    std::snprintf(name, sizeof name, "turn_%04d.png", i);
    EXPECT_TRUE(fs::exists(dir_ / name)) << name;
  }
  EXPECT_FALSE(fs::exists(dir_ / "turn_0004.png"));
}

TEST_F(CliRender, CameraLookingAlongItsUpVectorStillRenders) {
  writeQuadObj("quad.obj");
  RunResult r =
      run("render quad.obj --resolution 20,20 --camera-position 0,0,5 "
          "--camera-focal-point 0,0,0 --camera-view-up 0,0,1 -o up.png");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(fs::exists(dir_ / "up.png"));
  r = run("render quad.obj --camera-position 1,1,1 --camera-focal-point 1,1,1");
  EXPECT_EQ(r.exit_code, 2);
}

TEST_F(CliRender, InfoPrintsCountsWithoutRendering) {
  writeQuadObj("quad.obj");
  RunResult r = run("info quad.obj");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("triangles:  2"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("vertices:   4"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("max 1,1,0"), std::string::npos) << r.out;
  r = run("render quad.obj --info -o nothing.png");
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_NE(r.out.find("triangles:  2"), std::string::npos);
  EXPECT_FALSE(fs::exists(dir_ / "nothing.png"));
  EXPECT_EQ(run("info").exit_code, 2);
  EXPECT_EQ(run("info missing.obj").exit_code, 1);
}

// A quad with UVs, textured through --texture, seen straight on and unlit: each quarter of the
// quad shows one colour of the texture, as it is (the texture replaces the albedo).
TEST_F(CliRender, TextureFlagSuppliesTheAlbedo) {
  writeFile("quad.obj",
            "v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\n"
            "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
            "f 1/1 2/2 3/3 4/4\n");
  // 4x4 texels in 2x2 quadrants; row 0 is the top of the image: red, green / blue, white.
  const uint32_t quadrant[4] = {0xff0000ffu, 0xff00ff00u, 0xffff0000u, 0xffffffffu};
  uint32_t texels[16];
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 4; ++x) texels[y * 4 + x] = quadrant[(y / 2) * 2 + x / 2];
  ASSERT_TRUE(tessera::io::writePngRgba8((dir_ / "tex.png").string(), 4, 4, texels).ok());
  RunResult r =
      run("render quad.obj --texture tex.png --shading unlit --resolution 40,40 "
          "--camera-position 0,0,2.2 --camera-focal-point 0,0,0 "
          "--camera-view-angle 60 -o out.png");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  DecodedPng png;
  ASSERT_TRUE(tessera::test::decodePng((dir_ / "out.png").string(), png));
  auto rgb = [&](int x, int y) {
    return std::array<int, 3>{png.at(x, y, 0), png.at(x, y, 1), png.at(x, y, 2)};
  };
  // The centre of each quadrant blends only texels of one colour.
  EXPECT_EQ(rgb(12, 12), (std::array<int, 3>{255, 0, 0}));
  EXPECT_EQ(rgb(27, 12), (std::array<int, 3>{0, 255, 0}));
  EXPECT_EQ(rgb(12, 27), (std::array<int, 3>{0, 0, 255}));
  EXPECT_EQ(rgb(27, 27), (std::array<int, 3>{255, 255, 255}));
  r = run("render quad.obj --texture missing.png -o out2.png");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("missing.png"), std::string::npos);
  EXPECT_FALSE(fs::exists(dir_ / "out2.png"));
}

TEST_F(CliRender, TurntableToMp4) {
  if (std::system("command -v ffprobe > /dev/null") != 0)
    GTEST_SKIP() << "ffmpeg is not installed (scripts/setup.sh installs it)";
  writeQuadObj("quad.obj");
  RunResult r = run("render quad.obj --resolution 32,24 --turntable 6 --fps 12 -o turn.mp4");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string probe_command =
      "ffprobe -v error -count_frames -show_entries stream=nb_read_frames -of csv=p=0 '" +
      (dir_ / "turn.mp4").string() + "' > '" + (dir_ / "probe.txt").string() + "'";
  ASSERT_EQ(std::system(probe_command.c_str()), 0);
  EXPECT_EQ(slurp(dir_ / "probe.txt"), "6\n");
}

// A small scene with several materials and a concave polygon, compared with its reference image.
TEST_F(CliRender, MaterialsModelMatchesItsReferenceImage) {
  writeFile("scene.mtl",
            "newmtl red\nKd 0.8 0.1 0.1\n"
            "newmtl blue\nKd 0.1 0.2 0.8\n");
  writeFile("scene.obj",
            "mtllib scene.mtl\n"
            "v -1 0 -1\nv 1 0 -1\nv 1 0 1\nv -1 0 1\n"                   // floor
            "v -0.5 0 0\nv 0.5 0 0\nv 0.5 1 0\nv 0 0.4 0\nv -0.5 1 0\n"  // concave wall
            "usemtl blue\nf 1 4 3 2\n"
            "usemtl red\nf 5 6 7 8 9\n");
  RunResult r = run("render scene.obj --resolution 96,64 --shading flat -o scene.png");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  // Same machine arithmetic everywhere: allow rounding of a code here and there only.
  tessera::test::expectMatchesReference((dir_ / "scene.png").string(), "obj_materials", {2, 4});
}

// Framing fits near and far to the model: two planes 1% of the model's size apart resolve
// cleanly at any scale (no z-fighting), and the picture does not depend on the scale.
TEST_F(CliRender, FramingKeepsDepthPreciseForTinyAndHugeModels) {
  std::string reference_ids;
  for (double scale : {1e-4, 1.0, 1e5}) {
    std::ostringstream obj;
    auto v = [&](double x, double y, double z) {
      obj << "v " << x * scale << " " << y * scale << " " << z * scale << "\n";
    };
    v(-1, -1, 0.01), v(1, -1, 0.01), v(1, 1, 0.01), v(-1, 1, 0.01);  // front plane
    v(-1, -1, 0), v(1, -1, 0), v(1, 1, 0), v(-1, 1, 0);              // back plane
    obj << "f 1 2 3 4\nf 5 6 7 8\n";
    writeFile("planes.obj", obj.str());
    RunResult r = run("render planes.obj --resolution 48,32 --aov id -o ids.png");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    DecodedPng png;
    ASSERT_TRUE(tessera::test::decodePng((dir_ / "ids.png").string(), png));
    int front = 0, back = 0;
    for (int y = 0; y < png.height; ++y)
      for (int x = 0; x < png.width; ++x) {
        const int id = png.at(x, y, 0);
        front += id == 1 || id == 2;
        back += id == 3 || id == 4;
      }
    EXPECT_GT(front, 48 * 32 / 8) << "scale " << scale;
    EXPECT_EQ(back, 0) << "scale " << scale;
    const std::string ids = slurp(dir_ / "ids.png");
    if (reference_ids.empty()) reference_ids = ids;
    EXPECT_EQ(ids, reference_ids) << "scale " << scale;
  }
}

// The models in tests/data (tests/data/make_models.py), each rendered by the CLI (on its defaults
// but for the shading) and compared with its reference image: at most a code of rounding here and
// there.
TEST_F(CliRender, DataModelsMatchTheirReferenceImages) {
  struct Case {
    const char* model;
    const char* flags;
    const char* reference;
  };
  const Case cases[] = {
      {"box_corner.obj", "--shading flat", "box_corner_obj"},  // MTL, map_Kd, two materials
      // Smooth: the reference predates PBR, glTF's default shading since issue 19.
      {"scene.gltf", "--shading smooth", "scene_gltf"},          // hierarchy, texture, strip
      {"pyramid.stl", "--up +Z --shading flat", "pyramid_stl"},  // binary with a 'solid' header
  };
  for (const Case& c : cases) {
    const std::string out = (dir_ / (std::string(c.reference) + ".png")).string();
    RunResult r = run(std::string("render '") + TESSERA_TEST_DATA_DIR + "/" + c.model +
                      "' --resolution 120,90 " + c.flags + " -o '" + out + "'");
    ASSERT_EQ(r.exit_code, 0) << c.model << ": " << r.err;
    EXPECT_TRUE(r.err.empty()) << c.model << " warned: " << r.err;
    tessera::test::expectMatchesReference(out, c.reference, {2, 6});
  }
}

// glTF is drawn with its metallic-roughness materials unless --shading says otherwise; other
// formats keep smooth (per-pixel Lambert) shading.
TEST_F(CliRender, GltfDefaultsToPbrShadingAndObjToSmooth) {
  auto crc = [&](const std::string& model, const std::string& flags) {
    RunResult r =
        run(std::string("render '") + TESSERA_TEST_DATA_DIR + "/" + model +
            "' --resolution 60,40 --crc -o '" + (dir_ / "crc.png").string() + "' " + flags);
    EXPECT_EQ(r.exit_code, 0) << r.err;
    return r.out;
  };
  EXPECT_EQ(crc("scene.gltf", ""), crc("scene.gltf", "--shading pbr"));
  EXPECT_NE(crc("scene.gltf", ""), crc("scene.gltf", "--shading smooth"));
  EXPECT_EQ(crc("box_corner.obj", ""), crc("box_corner.obj", "--shading smooth"));
  EXPECT_NE(crc("box_corner.obj", ""), crc("box_corner.obj", "--shading pbr"));
}

// A glTF quad in z = 0 facing +z (single-sided), seen by camera 0 from z = 4 and by camera 1
// from z = -4, turned half about +y to look at its back.
TEST_F(CliRender, CameraIndexDrawsFromTheFilesCameraAndCountsThemPastTheEnd) {
  writeFile("cams.gltf",
            R"({"asset":{"version":"2.0"},"scenes":[{"nodes":[0,1,2]}],)"
            R"("nodes":[{"mesh":0},{"camera":0,"translation":[0,0,4]},)"
            R"({"camera":1,"translation":[0,0,-4],"rotation":[0,1,0,0]}],)"
            R"("cameras":[{"type":"perspective","perspective":{"yfov":1.0,"znear":0.5,"zfar":20}},)"
            R"({"type":"perspective","perspective":{"yfov":1.0,"znear":0.5,"zfar":20}}],)"
            R"("meshes":[{"primitives":[{"attributes":{"POSITION":0},"indices":1}]}],)"
            R"("accessors":[{"bufferView":0,"componentType":5126,"type":"VEC3","count":4,)"
            R"("min":[-1,-1,0],"max":[1,1,0]},)"
            R"({"bufferView":1,"componentType":5123,"type":"SCALAR","count":6}],)"
            R"("bufferViews":[{"buffer":0,"byteOffset":0,"byteLength":48},)"
            R"({"buffer":0,"byteOffset":48,"byteLength":12}],)"
            R"("buffers":[{"byteLength":60,"uri":"data:application/octet-stream;base64,)"
            R"(AACAvwAAgL8AAAAAAACAPwAAgL8AAAAAAACAPwAAgD8AAAAA)"
            R"(AACAvwAAgD8AAAAAAAABAAIAAAACAAMA"}]})");
  const auto ids = [&](int index) {
    std::set<int> seen;
    RunResult r = run("render cams.gltf --resolution 40,40 --aov id --camera-index " +
                      std::to_string(index) + " -o id.png");
    EXPECT_EQ(r.exit_code, 0) << r.err;
    DecodedPng png;
    if (!tessera::test::decodePng((dir_ / "id.png").string(), png)) return seen;
    // The quad's centre is the image's; its corners are off the quad (it spans 46% of the
    // height at yfov 1 from 4 units).
    seen.insert(png.at(20, 20, 0));
    seen.insert(png.at(0, 0, 0));
    return seen;
  };
  // From the front: the corner is background (0), the centre one of the quad's triangles (1, 2).
  const std::set<int> front = ids(0);
  ASSERT_EQ(front.size(), 2u);
  EXPECT_EQ(front.count(0), 1u);
  EXPECT_TRUE(front.count(1) + front.count(2) == 1u);
  EXPECT_EQ(ids(1), std::set<int>{0}) << "the back of a single-sided quad shows nothing";
  RunResult past = run("render cams.gltf --camera-index 2 -o past.png");
  EXPECT_EQ(past.exit_code, 1);
  EXPECT_NE(past.err.find("the model has 2 cameras (0 to 1)"), std::string::npos) << past.err;
  EXPECT_FALSE(fs::exists(dir_ / "past.png"));
}

// assimp-testmodels' glTF camera sample: a unit square tilted 45 degrees away about +x, seen by
// a perspective camera (yfov 0.7) and an orthographic one (xmag = ymag = 1), both at
// (0.5, 0.5, 3). Where its edges land follows from the file's numbers: perspective, bottom edge
// (y 0, z 0) at row 150 + 150 tan(atan(0.5 / 3)) / tan(0.35) = 218.6, top edge (y 0.707,
// z -0.707) at 150 - 150 (0.207 / 3.707) / tan(0.35) = 126.9, narrower than the bottom;
// orthographic, 150 pixels a unit: columns 75 to 225, rows 118.9 to 225, as wide at the top.
TEST_F(CliRender, AssimpCameraSampleIsSeenFromItsCameras) {
  const std::string model = "/usr/share/assimp/models/glTF2/cameras/Cameras.gltf";
  ASSERT_TRUE(fs::exists(model)) << model << ": scripts/setup.sh installs assimp-testmodels";
  struct Extent {
    int top = 1 << 30, bottom = -1, top_width = 0, bottom_width = 0;
  };
  const auto extent = [&](int index) {
    Extent e;
    RunResult r = run("render '" + model + "' --resolution 300,300 --aov id --camera-index " +
                      std::to_string(index) + " -o id.png");
    EXPECT_EQ(r.exit_code, 0) << r.err;
    DecodedPng png;
    if (!tessera::test::decodePng((dir_ / "id.png").string(), png)) return e;
    std::vector<int> width(300, 0);
    for (int y = 0; y < png.height; ++y)
      for (int x = 0; x < png.width; ++x)
        if (png.at(x, y, 0) != 0) {
          ++width[static_cast<size_t>(y)];
          e.top = std::min(e.top, y);
          e.bottom = std::max(e.bottom, y);
        }
    if (e.bottom >= 0) {
      e.top_width = width[static_cast<size_t>(e.top + 1)];
      e.bottom_width = width[static_cast<size_t>(e.bottom - 1)];
    }
    return e;
  };
  const Extent perspective = extent(0);
  EXPECT_NEAR(perspective.top, 127, 1);
  EXPECT_NEAR(perspective.bottom, 218, 1);
  EXPECT_LT(perspective.top_width + 10, perspective.bottom_width);
  const Extent orthographic = extent(1);
  EXPECT_NEAR(orthographic.top, 119, 1);
  EXPECT_NEAR(orthographic.bottom, 224, 1);
  EXPECT_NEAR(orthographic.top_width, 150, 1);
  EXPECT_EQ(orthographic.top_width, orthographic.bottom_width);
}

// A unit box standing on a 10 x 10 floor, with vertex normals (smooth shading keeps its faces).
std::string boxOnFloorObj() {
  std::string obj = "v -5 0 -5\nv -5 0 5\nv 5 0 5\nv 5 0 -5\nvn 0 1 0\nf 1//1 2//1 3//1 4//1\n";
  const char* normals = "vn 1 0 0\nvn -1 0 0\nvn 0 1 0\nvn 0 -1 0\nvn 0 0 1\nvn 0 0 -1\n";
  obj += normals;
  for (int i = 0; i < 8; ++i)
    obj += std::string("v ") + (i & 1 ? "0.5" : "-0.5") + (i & 2 ? " 1" : " 0") +
           (i & 4 ? " 0.5" : " -0.5") + "\n";
  // Box corners are vertices 5..12; faces counter-clockwise from outside, normals 2..7.
  obj +=
      "f 6//2 8//2 12//2 10//2\nf 5//3 9//3 11//3 7//3\nf 7//4 11//4 12//4 8//4\n"
      "f 5//5 6//5 10//5 9//5\nf 9//6 10//6 12//6 11//6\nf 5//7 7//7 8//7 6//7\n";
  return obj;
}

TEST_F(CliRender, ShadowsDarkenWhatTheBoxHidesFromTheLight) {
  writeFile("box.obj", boxOnFloorObj());
  // Straight down on the floor; the light travels +x and down: the box's shadow is the floor
  // from x = 0.5 to 1 (the pixels right of the image centre).
  const std::string common =
      "render box.obj --resolution 200,200 --camera-position 0.5,6,0 --camera-focal-point "
      "0.5,0,0 --camera-view-up 0,0,-1 --camera-view-angle 50 --light directional:1,-2,0:1,1,1:0.6 "
      "--ambient 0.1,0.1,0.1 ";
  RunResult on = run(common + "--shadows -o on.png");
  ASSERT_EQ(on.exit_code, 0) << on.err;
  RunResult off = run(common + "-o off.png");
  ASSERT_EQ(off.exit_code, 0) << off.err;
  DecodedPng a, b;
  ASSERT_TRUE(tessera::test::decodePng((dir_ / "on.png").string(), a));
  ASSERT_TRUE(tessera::test::decodePng((dir_ / "off.png").string(), b));
  // World x = 0.75 and x = -2 on the floor's z = 0 line: 200 px span 2 * 6 tan(25) units.
  const float px_per_unit = 100.0f / (6.0f * std::tan(25.0f * 3.14159265f / 180.0f));
  const int shadow_x = static_cast<int>(100 + 0.25f * px_per_unit);
  const int lit_x = static_cast<int>(100 - 2.5f * px_per_unit);
  EXPECT_LT(a.at(shadow_x, 100, 1) + 40, b.at(shadow_x, 100, 1));
  EXPECT_GT(b.at(lit_x, 100, 1), 60);
  EXPECT_EQ(a.at(lit_x, 100, 1), b.at(lit_x, 100, 1));
}

TEST_F(CliRender, ShadowsAreDrawnOnTheVulkanBackends) {
  // The Vulkan backends draw the CPU's shadow maps (docs/vulkan-features.md): the same shadow as
  // the cpu backend's, where the box hides the floor from the light, and the lit floor unchanged. A
  // tessera built without them (the sanitizer builds) refuses the backend itself, a usage error.
  writeFile("box.obj", boxOnFloorObj());
  const std::string common =
      "render box.obj --resolution 200,200 --camera-position 0.5,6,0 --camera-focal-point "
      "0.5,0,0 --camera-view-up 0,0,-1 --camera-view-angle 50 --light directional:1,-2,0:1,1,1:0.6 "
      "--ambient 0.1,0.1,0.1 ";
  const float px_per_unit = 100.0f / (6.0f * std::tan(25.0f * 3.14159265f / 180.0f));
  // Read only where tessera has the Vulkan backends.
  [[maybe_unused]] const int shadow_x = static_cast<int>(100 + 0.25f * px_per_unit);
  [[maybe_unused]] const int lit_x = static_cast<int>(100 - 2.5f * px_per_unit);
  for (const char* backend : {"vulkan", "vulkan-raster"}) {
    RunResult on = run(common + "--shadows --backend " + backend + " -o on.png");
#if TESSERA_EXE_HAS_VULKAN
    ASSERT_EQ(on.exit_code, 0) << backend << ": " << on.err;
    RunResult off = run(common + "--backend " + backend + " -o off.png");
    ASSERT_EQ(off.exit_code, 0) << off.err;
    DecodedPng a, b;
    ASSERT_TRUE(tessera::test::decodePng((dir_ / "on.png").string(), a));
    ASSERT_TRUE(tessera::test::decodePng((dir_ / "off.png").string(), b));
    EXPECT_LT(a.at(shadow_x, 100, 1) + 40, b.at(shadow_x, 100, 1)) << backend;
    EXPECT_GT(b.at(lit_x, 100, 1), 60) << backend;
    EXPECT_EQ(a.at(lit_x, 100, 1), b.at(lit_x, 100, 1)) << backend;
#else
    EXPECT_EQ(on.exit_code, 2) << backend;
    EXPECT_NE(on.err.find("flag '--backend': expected one of cpu"), std::string::npos) << on.err;
    EXPECT_FALSE(fs::exists(dir_ / "on.png"));
#endif
  }
#if TESSERA_EXE_HAS_VULKAN
  RunResult bench = run("bench box.obj --shadows --backend vulkan --frames 1 --resolution 160,120");
  EXPECT_EQ(bench.exit_code, 0) << bench.err;
#endif
}
