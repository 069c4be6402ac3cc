#include <tessera/render/frame.h>

#include <limits>

namespace tessera {

void Frame::resize(int w, int h, bool with_normals) {
  width = w;
  height = h;
  size_t n = pixelCount();
  color.resize(n);
  depth.resize(n, std::numeric_limits<float>::infinity());
  triangle_id.resize(n);
  if (with_normals)
    normal.resize(n);
  else
    normal.clear();
}

}  // namespace tessera
