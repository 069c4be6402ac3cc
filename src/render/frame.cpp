#include <tessera/render/frame.h>

#include <limits>
#include <vector>

#include "render/page_pool.h"

namespace tessera {

void Frame::resize(int w, int h, bool with_depth, bool with_ids, bool with_normals,
                   bool with_coverage) {
  width = w;
  height = h;
  const size_t n = pixelCount();
  if (color.capacity() < n) {
    // The tile stage writes the colour 64 pixels a row, each row in another 4 KiB page: in huge
    // pages (where the system has them) a tile's stores stay within the TLB.
    std::vector<uint32_t> fresh;
    fresh.reserve(n);
    render::adviseHugePages(fresh.data(), n * sizeof(uint32_t));
    color.swap(fresh);
  }
  color.resize(n);
  depth.resize(with_depth ? n : 0, std::numeric_limits<float>::infinity());
  triangle_id.resize(with_ids ? n : 0);
  normal.resize(with_normals ? n : 0);
  coverage.resize(with_coverage ? n : 0);
}

}  // namespace tessera
