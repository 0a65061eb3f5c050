// libFuzzer harness: scene text → loadSceneFromText (the CLI's loader) → captureSequence
// (integrator/capture/capture.h): the Scene is built (BVH, lights, textures, camera), one
// frame is rendered at 1 spp, then exposed and developed through the sensor and ISP when
// the scene has a sensor. Bad input must end in InputError; anything else (a crash, a
// sanitizer report, another exception, an abort, a NaN in any output) is a finding.
//
// Caps that keep one execution in milliseconds (the scene is otherwise as loaded): the
// image is the centre crop of at most kMaxSide × kMaxSide pixels (the sensor shrinks with it,
// so the pixel pitch stays), 1 spp, at most kMaxDepth bounces, one frame of a sequence, at
// most kMaxBrackets brackets, one thread. A scene that read a file larger than kMaxFileBytes
// (an absolute path to a big file on this machine) is loaded but not rendered.
//
// Relative paths resolve against a private directory made once per process (mkdtemp),
// holding tiny stand-ins for the files the example scenes and the seeds name (meshes, a
// texture, environment maps); it is removed at exit.
#include <stdlib.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <system_error>
#include <vector>

#include "fuzz/fuzz_check.h"
#include "integrator/capture/capture.h"
#include "integrator/scene/scene_loader.h"
#include "sensor/base/input_error.h"
#include "sensor/io/exr_io.h"
#include "sensor/io/png_io.h"

namespace {

constexpr int kMaxSide = 8;
constexpr int kMaxDepth = 4;
constexpr std::size_t kMaxBrackets = 3;
constexpr std::uintmax_t kMaxFileBytes = std::uintmax_t{1} << 20;

std::filesystem::path gBaseDir;
bool gVerbose = false;  // CAMSIM_FUZZ_VERBOSE=1: print each InputError (to triage seeds)

void removeBaseDir() {
  std::error_code ignored;
  std::filesystem::remove_all(gBaseDir, ignored);  // our own mkdtemp directory
}

void writeText(const std::filesystem::path& file, const char* text) {
  std::filesystem::create_directories(file.parent_path());
  std::ofstream(file) << text;
}

// Stand-ins: a two-triangle quad (OBJ with texture coordinates, PLY), glTF assets, a
// spectral table, a 4×4 PNG and an 8×4 lat-long EXR, under the names the example scenes and the seed corpus use.
void writeAssets(const std::filesystem::path& dir) {
  const char* obj =
      "v -1 0 -1\nv 1 0 -1\nv 1 0 1\nv -1 0 1\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
      "vn 0 1 0\nf 1/1/1 2/2/1 3/3/1\nf 1/1/1 3/3/1 4/4/1\n";
  for (const char* name :
       {"mesh.obj", "meshes/stanford-bunny.obj", "assets/stanford-bunny.obj", "assets/spot.obj"})
    writeText(dir / name, obj);
  const char* ply =
      "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
      "property float z\nelement face 2\nproperty list uchar int vertex_indices\nend_header\n"
      "-1 0 -1\n1 0 -1\n1 0 1\n-1 0 1\n3 0 1 2\n3 0 2 3\n";
  for (const char* name : {"mesh.ply", "bunny.ply"}) writeText(dir / name, ply);

  // glTF: one triangle (a data-URI buffer, a metallic-roughness material) and two lamps.
  writeText(dir / "assets/Cube/Cube.gltf",
            R"({"asset":{"version":"2.0"},"buffers":[{"byteLength":36,"uri":"data:application/)"
            R"(octet-stream;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAA"}],)"
            R"("bufferViews":[{"buffer":0,"byteLength":36}],"accessors":[{"bufferView":0,)"
            R"("componentType":5126,"count":3,"type":"VEC3","min":[0,0,0],"max":[1,1,0]}],)"
            R"("materials":[{"pbrMetallicRoughness":{"baseColorFactor":[0.8,0.5,0.2,1],)"
            R"("metallicFactor":0.5,"roughnessFactor":0.4}}],"meshes":[{"primitives":[)"
            R"({"attributes":{"POSITION":0},"material":0}]}],"nodes":[{"mesh":0}],)"
            R"("scenes":[{"nodes":[0]}],"scene":0})");
  writeText(dir / "assets/lamps.gltf",
            R"({"asset":{"version":"2.0"},"extensionsUsed":["KHR_lights_punctual"],)"
            R"("extensions":{"KHR_lights_punctual":{"lights":[{"type":"point","intensity":400,)"
            R"("color":[1.0,0.92,0.82]},{"type":"spot","intensity":600,"spot":{)"
            R"("innerConeAngle":0.25,"outerConeAngle":0.45}}]}},"nodes":[{"translation":)"
            R"([0,1.9,0.6],"extensions":{"KHR_lights_punctual":{"light":0}}},{"translation":)"
            R"([0.9,1.6,1.2],"rotation":[-0.3535534,0.3535534,0.1464466,0.8535534],)"
            R"("extensions":{"KHR_lights_punctual":{"light":1}}}],"scenes":[{"nodes":[0,1]}],)"
            R"("scene":0})");

  writeText(dir / "tables/colorchecker_classic_reflectance.csv",
            "wavelength_nm,patch13,patch19\n380,0.05,0.9\n550,0.2,0.9\n780,0.6,0.9\n");

  camsim::PngImage png{4, 4, 3, 8, {}};
  for (int i = 0; i < 4 * 4 * 3; ++i) png.samples.push_back(static_cast<std::uint16_t>(i * 5));
  for (const char* name : {"texture.png", "textures/speckle.png"}) {
    std::filesystem::create_directories((dir / name).parent_path());
    camsim::writePng(dir / name, png);
  }
  camsim::Image env(8, 4, {"R", "G", "B"});
  for (std::size_t i = 0; i < env.pixels.size(); ++i)
    env.pixels[i] = 0.25f + 0.1f * static_cast<float>(i % 7);
  for (const char* name : {"env.exr", "env/sky.exr", "env/studio.exr"}) {
    std::filesystem::create_directories((dir / name).parent_path());
    camsim::writeExr(dir / name, env, {}, std::nullopt);
  }
}

bool readsBigFile(const camsim::SceneDescription& desc) {
  for (const std::filesystem::path& f : desc.inputFiles) {
    std::error_code ec;
    const std::uintmax_t bytes = std::filesystem::file_size(f, ec);
    if (!ec && bytes > kMaxFileBytes) return true;
  }
  return false;
}

void capScene(camsim::SceneDescription& desc) {
  camsim::PhysicalCameraParams& camera = desc.camera;
  const glm::ivec2 side = glm::min(camera.resolution, glm::ivec2(kMaxSide));
  camera.sensorSize *= glm::dvec2(side) / glm::dvec2(camera.resolution);  // centre crop
  camera.resolution = side;
  desc.render.spp = 1;
  desc.render.maxDepth = std::min(desc.render.maxDepth, kMaxDepth);
  if (desc.frames) desc.frames->count = 1;
  if (desc.sensor && desc.sensor->bracketEv.size() > kMaxBrackets)
    desc.sensor->bracketEv.resize(kMaxBrackets);
}

void checkFinite(const camsim::Image& image) {
  FUZZ_CHECK(image.pixels.size() == static_cast<std::size_t>(image.width) *
                                        static_cast<std::size_t>(image.height) *
                                        image.channels.size());
  for (const float v : image.pixels) FUZZ_CHECK(std::isfinite(v));
}

void checkCapture(const camsim::CaptureResult& r) {
  FUZZ_CHECK(!r.cancelled);
  const glm::ivec2 res = r.description.camera.resolution;
  FUZZ_CHECK(r.film.width == res.x && r.film.height == res.y);
  checkFinite(r.film);
  for (const float v : r.film.pixels) FUZZ_CHECK(v >= 0.0f);  // CIE XYZ of light: ≥ 0
  checkFinite(r.picture);
  FUZZ_CHECK(std::isfinite(r.displayExposure) && std::isfinite(r.exposureScale));
  // AOVs: depth and distance are +inf where nothing is hit; never NaN.
  for (const float v : r.aovs.pixels) FUZZ_CHECK(!std::isnan(v));
  if (!r.description.sensor) return;
  checkFinite(r.sensorFilm);
  FUZZ_CHECK(!r.frames.empty() && r.referenceFrame < r.frames.size());
  FUZZ_CHECK(r.developed.has_value());
  for (const camsim::CaptureFrame& f : r.frames) {
    FUZZ_CHECK(std::isfinite(f.exposureTimeS) && f.exposureTimeS > 0.0);
    checkFinite(f.electrons);
    FUZZ_CHECK(!f.raws.empty());
    for (const double g : f.whiteBalanceGains) FUZZ_CHECK(std::isfinite(g) && g > 0.0);
  }
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  std::string pattern =
      (std::filesystem::temp_directory_path() / "camsim_fuzz_render_XXXXXX").string();
  FUZZ_CHECK(::mkdtemp(pattern.data()) != nullptr);
  gBaseDir = pattern;
  gVerbose = std::getenv("CAMSIM_FUZZ_VERBOSE") != nullptr;
  std::atexit(removeBaseDir);
  writeAssets(gBaseDir);
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    camsim::SceneDescription desc = camsim::loadSceneFromText(text, "fuzz.yaml", gBaseDir);
    if (readsBigFile(desc)) return 0;
    capScene(desc);
    camsim::CaptureOptions options;
    options.threads = 1;
    int frames = 0;
    camsim::captureSequence(std::move(desc), options, [&](camsim::CaptureResult&& r, int) {
      checkCapture(r);
      ++frames;
    });
    FUZZ_CHECK(frames == 1);
  } catch (const camsim::InputError& e) {
    if (gVerbose) std::fprintf(stderr, "InputError: %s\n", e.what());
  }
  return 0;
}
