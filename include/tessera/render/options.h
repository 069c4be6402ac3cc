// Per-frame render options.
#pragma once

namespace tessera {

struct RenderOptions {
  int width = 480;
  int height = 480;
  bool depth = true;     // fill Frame::depth (the depth AOV)
  bool ids = true;       // fill Frame::triangle_id (the id AOV)
  bool normals = false;  // fill Frame::normal (the normal AOV)
  bool lines = true;     // draw Scene::lines and the axes the scene asks for (needs depth: a frame
                         // that draws lines has a depth buffer whatever `depth` says)
};

}  // namespace tessera
