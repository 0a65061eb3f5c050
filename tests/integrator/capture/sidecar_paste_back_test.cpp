// The sidecar's `camera`, `sensor` and `isp` blocks are scene text (docs/output.md): for
// every example scene in scenes/, at a tiny resolution and 1 spp, render, paste the three
// blocks of NAME.json (less their `derived` parts) back over the scene's own, render again
// and get the same bytes in every file. The sidecar leaves out the camera's `motion`,
// `lens_transmittance` and `gltf` (docs/output.md): the paste-back keeps the scene's.
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "integrator/capture/capture.h"
#include "integrator/capture/capture_writer.h"
#include "integrator/scene/scene_loader.h"
#include "sensor/base/yaml_edit.h"
#include "sensor/base/yaml_reader.h"
#include "sensor/io/exr_io.h"
#include "tests/support/temp_dir.h"
#include "tests/support/text_file.h"

namespace camsim {
namespace {

const std::filesystem::path kScenes = std::filesystem::path(CAMSIM_SOURCE_DIR) / "scenes";

YamlEdit edit(const std::string& path, const std::string& value) {
  YamlEdit e;
  e.path = path;
  e.value = value;
  e.key = path;
  return e;
}

// The scene's value at camera.KEY as flow YAML, if it has one.
std::optional<std::string> cameraValue(const std::string& sceneText, const std::string& key) {
  YamlMap top(parseYaml(sceneText, "scene"));
  const std::optional<YamlValue> camera = top.find("camera");
  if (!camera) return std::nullopt;
  YamlMap c(*camera);
  const std::optional<YamlValue> v = c.find(key);
  if (!v) return std::nullopt;
  return yamlFlowText(*v);
}

// The scene made tiny and quick: 24 × 16 px, 1 spp, one frame (no `frames` sequence, so
// no AOVs either: motion vectors need one).
std::string tiny(const std::string& text, const std::string& file) {
  return applyYamlEdits(text, file,
                        {edit("render.spp", "1"), edit("camera.resolution", "[24, 16]"),
                         edit("frames", "null"), edit("render.aovs", "null")})
      .text;
}

// Renders `text` into `dir` (reproducible: no wall times); returns the files written.
std::vector<std::filesystem::path> render(const std::string& text,
                                          const std::filesystem::path& dir) {
  CaptureResult r = capture(loadSceneFromText(text, "scene.yaml", kScenes));
  std::filesystem::create_directories(dir);
  CaptureOutputOptions out;
  out.directory = dir;
  out.reproducible = true;
  std::vector<std::filesystem::path> files = writeCapture(r, out).files;
  std::sort(files.begin(), files.end());
  return files;
}

// `scene` with the sidecar's camera/sensor/isp blocks, less `derived`, in place of its own.
std::string pasteBack(const std::string& scene, const std::string& sidecar) {
  std::vector<YamlEdit> drop;
  const YamlValue json = parseYaml(sidecar, "sidecar");
  YamlMap blocks(json);
  for (const char* block : {"camera", "sensor", "isp"})
    if (blocks.has(block)) drop.push_back(edit(std::string(block) + ".derived", "null"));
  const std::string inputs = applyYamlEdits(sidecar, "sidecar", drop).text;
  YamlMap top(parseYaml(inputs, "sidecar inputs"));
  std::vector<YamlEdit> paste;
  for (const char* block : {"camera", "sensor", "isp"})
    if (auto v = top.find(block)) paste.push_back(edit(block, yamlFlowText(*v)));
  for (const char* key : {"motion", "lens_transmittance"})
    if (auto v = cameraValue(scene, key)) paste.push_back(edit(std::string("camera.") + key, *v));
  return applyYamlEdits(scene, "scene", paste).text;
}

// The camera, sensor and isp blocks of a scene (for a failure's message).
std::string blocks(const std::string& scene) {
  YamlMap top(parseYaml(scene, "scene"));
  std::string text;
  for (const char* block : {"camera", "sensor", "isp"})
    if (auto v = top.find(block)) text += std::string(block) + ": " + yamlFlowText(*v) + "\n";
  return text;
}

bool sameBytes(const std::string& a, const std::string& b) {
  // std::equal, not memcmp: an empty file's buffer may be null (UBSan: docs/testing.md).
  return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin());
}

// Two EXR files hold the same channels, pixels (bit for bit) and attributes, but for
// camsim:scene_fnv1a64: the hash of the scene text, which the paste-back rewrote.
bool sameExr(const std::filesystem::path& a, const std::filesystem::path& b) {
  const ExrFile x = readExr(a), y = readExr(b);
  const auto bits = [](const std::vector<float>& v) {
    std::vector<std::uint32_t> u(v.size());
    for (std::size_t i = 0; i < v.size(); ++i) u[i] = std::bit_cast<std::uint32_t>(v[i]);
    return u;
  };
  Metadata mx = x.metadata, my = y.metadata;
  for (Metadata* m : {&mx, &my})
    std::erase_if(*m, [](const auto& kv) { return kv.first == "camsim:scene_fnv1a64"; });
  return x.image.width == y.image.width && x.image.height == y.image.height &&
         x.image.channels == y.image.channels && bits(x.image.pixels) == bits(y.image.pixels) &&
         mx == my;
}

// Renders `scene`, pastes its sidecar back, renders again: every file the same (a DNG's
// header also holds the scene's hash; its pixels are the raw EXR's raw.DN, compared there).
void checkPasteBack(const std::string& scene) {
  test::TempDir dir;
  const std::vector<std::filesystem::path> first = render(scene, dir.path() / "first");
  std::filesystem::path json;
  for (const auto& f : first)
    if (f.extension() == ".json") json = f;
  ASSERT_FALSE(json.empty());
  const std::string pasted = pasteBack(scene, test::readFile(json));
  const std::vector<std::filesystem::path> second = render(pasted, dir.path() / "second");
  ASSERT_EQ(first.size(), second.size()) << blocks(pasted);
  std::string differ;
  for (std::size_t i = 0; i < first.size(); ++i) {
    EXPECT_EQ(first[i].filename(), second[i].filename());
    const std::string ext = first[i].extension().string();
    const bool same = ext == ".exr" ? sameExr(first[i], second[i])
                      : ext == ".dng"
                          ? true
                          : sameBytes(test::readFile(first[i]), test::readFile(second[i]));
    if (!same) differ += " " + first[i].filename().string();
  }
  EXPECT_TRUE(differ.empty()) << "differ:" << differ << "\nthe pasted camera, sensor, isp:\n"
                              << blocks(pasted);
}

TEST(SidecarPasteBack, EveryExampleSceneRendersTheSameBytes) {
  int scenes = 0;
  for (const auto& entry : std::filesystem::directory_iterator(kScenes)) {
    const std::filesystem::path file = entry.path();
    if (file.extension() != ".yaml") continue;
    const std::string text = test::readFile(file);
    if (!YamlMap(parseYaml(text, file.string())).has("camera")) continue;  // a dataset manifest
    SCOPED_TRACE(file.filename().string());
    try {
      checkPasteBack(tiny(text, file.string()));
    } catch (const InputError& e) {
      ADD_FAILURE() << file.filename() << ": " << e.what();
    }
    ++scenes;
  }
  EXPECT_GE(scenes, 12);  // every example but the dataset manifest
}

// A field limit below the one a `distortion` block gets is kept: found by probing, the
// sidecar wrote a plain opencv camera with max_field_angle_deg 30 as a bare `distortion`,
// and the pasted-back scene imaged the pixels beyond 30°.
TEST(SidecarPasteBack, AnOpenCvFieldLimitIsKept) {
  for (const char* projection : {"{model: opencv, max_field_angle_deg: 30}",
                                 "{model: opencv, k1: -0.2, max_field_angle_deg: 30}"}) {
    SCOPED_TRACE(projection);
    const std::filesystem::path file = kScenes / "cornell_box.yaml";
    const std::string text =
        applyYamlEdits(
            tiny(test::readFile(file), file.string()), file.string(),
            {edit("camera.focal_length_mm", "10"), edit("camera.projection", projection)})
            .text;
    checkPasteBack(text);
  }
}

}  // namespace
}  // namespace camsim
