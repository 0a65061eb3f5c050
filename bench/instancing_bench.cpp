// instancing_bench: what a scene costs to load and to build, the row docs/performance.md
// ("Instancing") gives for 1,000 Stanford bunnies as instances of one mesh against 1,000
// copies (bench/instancing/, written by scripts/make_instancing_bench.py).
//
//   load   loadScene(): the YAML and every mesh file it names (a copy reads its file again)
//   build  Scene(description): the shapes' arrays, Embree's BVHs (2 threads on this VM)
//   memory Embree's bytes after the build and at its peak (EmbreeScene's memory monitor);
//          the meshes' arrays (vector capacities; a shared mesh once) in the description and
//          in the shapes, plus sizeof(MeshInstance) per instance; the process's heap in use
//          after the build (glibc mallinfo2: also what the monitor does not see, such as
//          Embree's geometry objects) and its peak resident set (getrusage)
// and, with --render, the seconds of a render at the scene's spp (a check that both scenes
// give the same picture: the mean luminance). One scene per process, so that the peaks are
// its own.
//
// usage: instancing_bench SCENE.yaml [--render]
#include <malloc.h>
#include <sys/resource.h>

#include <chrono>
#include <cstdio>
#include <cstring>
#include <set>

#include "integrator/geometry/mesh_instance.h"
#include "integrator/render/render.h"
#include "integrator/scene/scene.h"
#include "integrator/scene/scene_loader.h"
#include "sensor/base/input_error.h"

namespace {

using camsim::MeshData;
using camsim::MeshInstance;
using camsim::TriangleMesh;

double seconds(std::chrono::steady_clock::time_point a, std::chrono::steady_clock::time_point b) {
  return std::chrono::duration<double>(b - a).count();
}

double megabytes(double bytes) {
  return bytes * 1e-6;
}

template <typename T>
double capacityBytes(const std::vector<T>& v) {
  return static_cast<double>(v.capacity() * sizeof(T));
}

double arrayBytes(const MeshData& m) {
  return capacityBytes(m.positions) + capacityBytes(m.normals) + capacityBytes(m.uvs) +
         capacityBytes(m.indices) + capacityBytes(m.tangents);
}

double arrayBytes(const TriangleMesh& m) {
  return capacityBytes(m.positions()) + capacityBytes(m.normals()) + capacityBytes(m.uvs()) +
         capacityBytes(m.indices()) + capacityBytes(m.faceNormals());
}

double heapBytes() {
  const struct mallinfo2 info = mallinfo2();
  return static_cast<double>(info.uordblks + info.hblkhd);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: instancing_bench SCENE.yaml [--render]\n");
    return 2;
  }
  const bool renderToo = argc > 2 && std::strcmp(argv[2], "--render") == 0;
  try {
    const double heapStart = heapBytes();
    const auto t0 = std::chrono::steady_clock::now();
    const camsim::SceneDescription description = camsim::loadScene(argv[1]);
    const auto t1 = std::chrono::steady_clock::now();
    const double heapBefore = heapBytes();
    const camsim::Scene scene(description);
    const auto t2 = std::chrono::steady_clock::now();
    const double heapAfter = heapBytes();

    double descriptionBytes = 0.0, shapeBytes = 0.0, triangles = 0.0;
    int instances = 0;
    std::set<const void*> counted;
    for (const camsim::ShapeDescription& s : description.shapes) {
      const MeshData& m = s.sharedMesh ? *s.sharedMesh : s.mesh;
      if (counted.insert(&m).second) descriptionBytes += arrayBytes(m);
    }
    for (std::size_t i = 0; i < scene.shapeCount(); ++i) {
      const camsim::Shape& shape = scene.shape(static_cast<int>(i));
      if (const auto* instance = dynamic_cast<const MeshInstance*>(&shape)) {
        ++instances;
        shapeBytes += sizeof(MeshInstance);
        if (counted.insert(instance->mesh().get()).second) {
          shapeBytes += arrayBytes(*instance->mesh());
          triangles += static_cast<double>(instance->mesh()->triangleCount());
        }
      } else if (const auto* mesh = dynamic_cast<const TriangleMesh*>(&shape)) {
        shapeBytes += arrayBytes(*mesh);
        triangles += static_cast<double>(mesh->triangleCount());
      }
    }
    struct rusage usage {};
    getrusage(RUSAGE_SELF, &usage);
    std::printf("scene %s\n", argv[1]);
    std::printf("shapes %zu, of them mesh instances %d; triangles stored %.0f\n",
                scene.shapeCount(), instances, triangles);
    std::printf("load %.2f s, build %.2f s\n", seconds(t0, t1), seconds(t1, t2));
    std::printf("Embree %.1f MB held, %.1f MB peak\n",
                megabytes(static_cast<double>(scene.geometry().embreeBytes())),
                megabytes(static_cast<double>(scene.geometry().embreePeakBytes())));
    std::printf("mesh arrays: description %.1f MB, shapes %.1f MB\n", megabytes(descriptionBytes),
                megabytes(shapeBytes));
    std::printf(
        "heap: the load added %.2f MB, the build %.2f MB; %.1f MB in use after it; peak RSS "
        "%.1f MB\n",
        megabytes(heapBefore - heapStart), megabytes(heapAfter - heapBefore), megabytes(heapAfter),
        static_cast<double>(usage.ru_maxrss) * 1e-3);
    if (renderToo) {
      camsim::RenderOptions options;
      options.spp = scene.settings().spp;
      options.threads = 2;
      const auto r0 = std::chrono::steady_clock::now();
      const camsim::RenderResult r =
          camsim::render(scene, camsim::SpectralResponse::cieXyz(), options);
      const auto r1 = std::chrono::steady_clock::now();
      const int y = r.image.channelIndex("Y");
      double mean = 0.0;
      for (int py = 0; py < r.image.height; ++py)
        for (int px = 0; px < r.image.width; ++px)
          mean += static_cast<double>(r.image.at(px, py, y));
      mean /= static_cast<double>(r.image.width) * r.image.height;
      std::printf("render %d spp: %.2f s, mean Y %.6g\n", options.spp, seconds(r0, r1), mean);
    }
  } catch (const camsim::InputError& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 2;
  }
  return 0;
}
