// Per-frame render options.
#pragma once

namespace tessera {

struct RenderOptions {
  int width = 480;
  int height = 480;
  bool normals = false;  // fill Frame::normal (the normal AOV)
  bool lines = true;     // draw Scene::lines and the axes the scene asks for
};

}  // namespace tessera
