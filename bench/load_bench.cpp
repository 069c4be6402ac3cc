// Load speed of the model loaders on a 1M-triangle mesh: a Wavefront OBJ and a binary STL of
// the same grid, written once into a temp folder. Run: build/bench/tessera_loadbench
#include <benchmark/benchmark.h>

#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <unistd.h>

#include <tessera/io/model_loader.h>

namespace {

namespace fs = std::filesystem;

// A 1000 x 500 grid of quads, two triangles each: 1,000,000 triangles, 501,501 vertices, on a
// gentle wave so no two facets are coplanar neighbours by accident.
constexpr int kQuadsX = 1000, kQuadsY = 500;
constexpr int64_t kTriangles = int64_t{2} * kQuadsX * kQuadsY;

float heightAt(int x, int y) {
  return 0.01f * static_cast<float>((x * 7 + y * 13) % 17);
}

struct TestFiles {
  fs::path folder, obj, stl;

  TestFiles() {
    folder = fs::temp_directory_path() / ("tessera_loadbench_" + std::to_string(::getpid()));
    fs::create_directories(folder);
    obj = folder / "grid.obj";
    stl = folder / "grid.stl";
    writeObj();
    writeStl();
  }
  ~TestFiles() {
    std::error_code ignored;
    fs::remove_all(folder, ignored);
  }

  static int vertexIndex(int x, int y) { return y * (kQuadsX + 1) + x; }

  void writeObj() const {
    std::string text;
    char line[96];
    for (int y = 0; y <= kQuadsY; ++y)
      for (int x = 0; x <= kQuadsX; ++x) {
        std::snprintf(line, sizeof line, "v %.4f %.4f %.4f\n", x * 0.01, y * 0.01,
                      static_cast<double>(heightAt(x, y)));
        text += line;
      }
    for (int y = 0; y < kQuadsY; ++y)
      for (int x = 0; x < kQuadsX; ++x) {
        const int a = vertexIndex(x, y) + 1, b = vertexIndex(x + 1, y) + 1;
        const int c = vertexIndex(x + 1, y + 1) + 1, d = vertexIndex(x, y + 1) + 1;
        std::snprintf(line, sizeof line, "f %d %d %d\nf %d %d %d\n", a, b, c, a, c, d);
        text += line;
      }
    std::ofstream(obj, std::ios::binary) << text;
  }

  void writeStl() const {
    std::vector<char> bytes(84 + 50 * static_cast<size_t>(kTriangles), 0);
    std::memcpy(bytes.data(), "binary grid", 11);
    const auto count = static_cast<uint32_t>(kTriangles);
    std::memcpy(bytes.data() + 80, &count, 4);
    char* facet = bytes.data() + 84;
    auto corner = [&](char* at, int x, int y) {
      const float p[3] = {x * 0.01f, y * 0.01f, heightAt(x, y)};
      std::memcpy(at, p, sizeof p);
    };
    for (int y = 0; y < kQuadsY; ++y)
      for (int x = 0; x < kQuadsX; ++x) {
        corner(facet + 12, x, y);
        corner(facet + 24, x + 1, y);
        corner(facet + 36, x + 1, y + 1);
        facet += 50;
        corner(facet + 12, x, y);
        corner(facet + 24, x + 1, y + 1);
        corner(facet + 36, x, y + 1);
        facet += 50;
      }
    std::ofstream(stl, std::ios::binary)
        .write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  }
};

const TestFiles& files() {
  static const TestFiles instance;
  return instance;
}

void loadAndCount(benchmark::State& state, const fs::path& path) {
  for (auto _ : state) {
    tessera::Expected<tessera::io::Model> model = tessera::io::loadModel(path);
    if (!model) {
      state.SkipWithError(model.error().message.c_str());
      return;
    }
    if (static_cast<int64_t>(model->mesh.triangleCount()) != kTriangles) {
      state.SkipWithError("wrong triangle count");
      return;
    }
    benchmark::DoNotOptimize(model->mesh.positions.data());
  }
  state.SetItemsProcessed(state.iterations() * kTriangles);
  state.counters["MB"] = static_cast<double>(fs::file_size(path)) / 1e6;
}

void BM_LoadObj1M(benchmark::State& state) {
  loadAndCount(state, files().obj);
}
void BM_LoadStlBinary1M(benchmark::State& state) {
  loadAndCount(state, files().stl);
}

BENCHMARK(BM_LoadObj1M)->Unit(benchmark::kMillisecond)->MinTime(2.0);
BENCHMARK(BM_LoadStlBinary1M)->Unit(benchmark::kMillisecond)->MinTime(2.0);

}  // namespace
