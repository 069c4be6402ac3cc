#include <tessera/render/frame.h>

#include <limits>

namespace tessera {

void Frame::resize(int w, int h, bool with_depth, bool with_ids, bool with_normals) {
  width = w;
  height = h;
  const size_t n = pixelCount();
  color.resize(n);
  depth.resize(with_depth ? n : 0, std::numeric_limits<float>::infinity());
  triangle_id.resize(with_ids ? n : 0);
  normal.resize(with_normals ? n : 0);
}

}  // namespace tessera
