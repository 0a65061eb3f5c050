#include "integrator/capture/resource_guard.h"

#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <set>
#include <string>

#include "integrator/render/path_guide.h"
#include "sensor/base/format.h"
#include "sensor/base/input_error.h"

namespace camsim {
namespace {

constexpr double kBytesPerGb = 1e9;
constexpr std::uint64_t kBytesPerTriangle = 100;
// A mesh instance: the MeshInstance, Embree's instance and its share of the top-level BVH,
// the Scene's per-shape entries (0.9 kB) and its ShapeDescription (2.3 kB), as
// docs/performance.md ("Instancing") measured them.
constexpr std::uint64_t kBytesPerInstance = 3300;

// "12.34 GB", "56.7 MB", "89 kB" (decimal units, as --max-memory-gb).
std::string gb(double bytes) {
  char buf[32];
  if (bytes >= 0.995e9)
    std::snprintf(buf, sizeof buf, "%.2f GB", bytes / kBytesPerGb);
  else if (bytes >= 0.995e6)
    std::snprintf(buf, sizeof buf, "%.1f MB", bytes * 1e-6);
  else
    std::snprintf(buf, sizeof buf, "%.0f kB", bytes * 1e-3);
  return buf;
}

}  // namespace

MemoryEstimate estimateRenderMemory(const SceneDescription& desc) {
  const auto pixels = static_cast<std::uint64_t>(desc.camera.resolution.x) *
                      static_cast<std::uint64_t>(desc.camera.resolution.y);
  MemoryEstimate m;
  // CIE XYZ film (3 doubles) → the XYZ image (3 floats), its RGB (3), the EXR image (R, G,
  // B, XYZ: 6) and the quick look (8-bit RGB). (Measured: 4096x4096 px peaks at 60 bytes/px,
  // this counts 75.)
  std::uint64_t filmChannels = 3;
  std::uint64_t imageBytesPerPixel = 4 * (3 + 3 + 6) + 3;
  if (desc.sensor) {
    const auto& cfa = desc.sensor->spec.cfa;
    filmChannels += cfa.isStacked() ? cfa.channels.size() : 1;
    // Per exposure frame: electrons, DN and raw EXR layers, DNG samples (float/uint16), and
    // the re-rendered film of a moving scene.
    const std::uint64_t frames = desc.sensor->bracketEv.empty() ? 1 : desc.sensor->bracketEv.size();
    imageBytesPerPixel += frames * (4 * 4 + 2) + 8 * 3;
  }
  // The amodal aov: two float channels per labelled shape (mask_film.h), in the AOV image
  // and again in the EXR image written with them.
  const std::vector<Aov>& aovs = desc.render.aovs;
  if (std::find(aovs.begin(), aovs.end(), Aov::kAmodal) != aovs.end())
    for (const ShapeDescription& shape : desc.shapes)
      if (!shape.className.empty()) imageBytesPerPixel += 2 * 2 * 4;
  m.film = pixels * filmChannels * 8;
  m.images = pixels * imageBytesPerPixel;
  // An instanced mesh is stored once (however many shapes place it), each instance costs
  // a constant.
  std::set<const MeshData*> shared;
  for (const ShapeDescription& shape : desc.shapes) {
    const MeshData* mesh = shape.sharedMesh ? shape.sharedMesh.get() : &shape.mesh;
    if (shape.sharedMesh && !shared.insert(mesh).second) {
      m.meshes += kBytesPerInstance;
      continue;
    }
    m.meshes += static_cast<std::uint64_t>(mesh->indices.size() / 3) * kBytesPerTriangle;
  }
  if (desc.render.guiding)
    m.guide =
        PathGuide::trainingBytes(desc.camera.resolution, desc.render.spp, desc.render.maxDepth);
  return m;
}

std::uint64_t physicalMemoryBytes() {
  const long pages = ::sysconf(_SC_PHYS_PAGES);
  const long pageSize = ::sysconf(_SC_PAGE_SIZE);
  if (pages <= 0 || pageSize <= 0) return 0;
  return static_cast<std::uint64_t>(pages) * static_cast<std::uint64_t>(pageSize);
}

double checkMaxMemoryGb(double gb, const SourceLocation& where, const std::string& option) {
  if (!(gb > 0.0 && gb <= kMaxMemoryGb))
    throw InputError(where, option,
                     "must be a number of GB in (0, " + formatShortest(kMaxMemoryGb) + "]");
  return gb;
}

void checkMemoryLimit(const SceneDescription& desc, std::optional<double> maxMemoryGb,
                      const std::string& option) {
  const MemoryEstimate m = estimateRenderMemory(desc);
  double limit = 0.0;
  std::string which;
  if (maxMemoryGb) {
    limit = *maxMemoryGb * kBytesPerGb;
    which = "the limit of " + gb(limit) + " set by " + option;
  } else {
    const std::uint64_t physical = physicalMemoryBytes();
    if (physical == 0) return;  // unknown: nothing sensible to compare with
    limit = kDefaultMemoryFraction * static_cast<double>(physical);
    which = "the memory limit of " + gb(limit) + " (75 % of the " +
            gb(static_cast<double>(physical)) + " of physical memory)";
  }
  if (static_cast<double>(m.total()) <= limit) return;
  const auto& res = desc.camera.resolution;
  throw InputError(
      {desc.sourceFile, 0, 0}, "",
      "this render needs an estimated " + gb(static_cast<double>(m.total())) + " of memory (film " +
          gb(static_cast<double>(m.film)) + ", output images " + gb(static_cast<double>(m.images)) +
          ", meshes " + gb(static_cast<double>(m.meshes)) +
          (m.guide ? ", path guiding's training " + gb(static_cast<double>(m.guide))
                   : std::string()) +
          " for " + std::to_string(res.x) + "x" + std::to_string(res.y) + " px), more than " +
          which + "; lower camera.resolution or raise the limit with " + option + " GB");
}

}  // namespace camsim
