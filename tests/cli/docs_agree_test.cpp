// The reference docs say what the code does: every key the scene loader accepts at the
// top level, in `camera`, `camera.aperture` and `isp` has a row in docs/scene-format.md
// (the loader lists the allowed keys when it meets an unknown one), and every file
// `camsim render` writes — plain, Bayer sensor with brackets, stacked sensor — has a row in
// docs/output.md.
#include <gtest/gtest.h>

#include <filesystem>
#include <set>
#include <string>
#include <vector>

#include "integrator/scene/scene_loader.h"
#include "sensor/base/input_error.h"
#include "tests/support/run_command.h"
#include "tests/support/temp_dir.h"
#include "tests/support/text_file.h"

namespace camsim {
namespace {

const std::filesystem::path kDocs = std::filesystem::path(CAMSIM_SOURCE_DIR) / "docs";

const char* kDocsScene =
    "camera: {position: [0, 0, 0], look_at: [0, 0, 1], resolution: [16, 12], CAMERA_EXTRA}\n"
    "SENSOR\n"
    "render: {spp: 1, max_depth: 0}\n"
    "shapes:\n"
    "  - {type: sphere, centre: [0, 0, 0], radius: 10, emission: {luminance: 50, two_sided: "
    "true}}\n"
    "TOP_EXTRA\n";

std::string scene(const std::string& cameraExtra, const std::string& sensor,
                  const std::string& topExtra) {
  std::string s = kDocsScene;
  s.replace(s.find("CAMERA_EXTRA"), 12, cameraExtra.empty() ? "f_number: 4" : cameraExtra);
  s.replace(s.find("SENSOR"), 6, sensor);
  s.replace(s.find("TOP_EXTRA"), 9, topExtra);
  return s;
}

// The keys the loader allows where `text` puts an unknown one.
std::vector<std::string> allowedKeys(const std::string& text) {
  try {
    loadSceneFromText(text, "docs.yaml", ".");
  } catch (const InputError& e) {
    const std::string m = e.what();
    const size_t at = m.find("allowed here: ");
    if (at == std::string::npos) return {};
    std::vector<std::string> keys;
    // Words of [a-z0-9_] (no std::regex: GCC 12 -O1 warns inside its std::function).
    const std::string list = m.substr(at + 14, m.find(')', at) - at - 14);
    std::string word;
    for (const char c : list + " ") {
      if ((c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_') {
        word += c;
      } else if (!word.empty()) {
        keys.push_back(word);
        word.clear();
      }
    }
    return keys;
  }
  return {};
}

TEST(DocsAgree, SceneFormatDocumentsEveryKeyTheLoaderAccepts) {
  const std::string doc = test::readFile(kDocs / "scene-format.md");
  ASSERT_FALSE(doc.empty());
  const std::string sensor = "sensor: {model: smartphone-1.4um}";
  struct Where {
    const char* name;
    std::string text;
    const char* prefix;  // how the doc's table names the key
  };
  const Where places[] = {
      {"top level", scene("", "", "zz_unknown: 1"), ""},
      {"camera", scene("f_number: 4, zz_unknown: 1", "", ""), ""},
      {"camera.aperture", scene("aperture: {zz_unknown: 1}", "", ""), "aperture."},
      {"isp", scene("", sensor, "isp: {zz_unknown: 1}"), ""},
  };
  for (const Where& w : places) {
    const std::vector<std::string> keys = allowedKeys(w.text);
    EXPECT_GE(keys.size(), 3u) << w.name;
    for (const std::string& k : keys)
      EXPECT_NE(doc.find("| `" + std::string(w.prefix) + k + "`"), std::string::npos)
          << w.name << " key '" << k << "' has no row in docs/scene-format.md";
  }
}

TEST(DocsAgree, OutputDocListsEveryFileRenderWrites) {
  const std::string doc = test::readFile(kDocs / "output.md");
  ASSERT_FALSE(doc.empty());
  test::TempDir dir;
  const std::vector<std::pair<std::string, std::string>> scenes = {
      {"plain", scene("", "", "")},
      {"bayer",
       scene("", "sensor: {model: smartphone-1.4um, noise: none, bracket_ev: [-1, 0]}", "")},
      {"stacked", scene("", "sensor: {model: ideal-xyz}", "")}};
  std::set<std::string> suffixes;
  for (const auto& [name, text] : scenes) {
    test::writeFile(dir.path() / (name + ".yaml"), "name: " + name + "\n" + text);
    const std::filesystem::path out = dir.path() / ("out_" + name);
    const test::RunResult r =
        test::runCamsim("render " + test::quote((dir.path() / (name + ".yaml")).string()) + " -o " +
                            test::quote(out.string()),
                        dir.path());
    ASSERT_EQ(r.exitCode, 0) << name << ": " << r.err;
    for (const auto& f : std::filesystem::directory_iterator(out)) {
      std::string file = f.path().filename().string();
      ASSERT_EQ(file.rfind(name, 0), 0u) << file;
      std::string suffix = file.substr(name.size());
      if (suffix.rfind("_ev", 0) == 0) {  // _ev-1.dng, _ev+0_raw.exr → _ev±X…
        const size_t end = suffix.find_first_not_of("-+0123456789", 3);
        suffix = "_ev±X" + suffix.substr(end);
      }
      suffixes.insert(suffix);
    }
  }
  EXPECT_GE(suffixes.size(), 8u);
  for (const std::string& s : suffixes) {
    const bool listed =
        doc.find("`NAME" + s + "`") != std::string::npos ||
        doc.find("`" + s + "`") != std::string::npos ||
        (s.rfind("_ev±X", 0) == 0 && doc.find("`NAME_ev±X.*`") != std::string::npos);
    EXPECT_TRUE(listed) << "docs/output.md has no row for NAME" << s;
  }
}

}  // namespace
}  // namespace camsim
