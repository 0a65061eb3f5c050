// Reading user-named input files (sensor/base/input_file.h) and the YAML alias guard
// (sensor/base/yaml_reader.cpp): both found by probing the command line — `camsim render
// /dev/zero` read forever, growing without bound, and a scene whose aliases nested nine deep
// (the "billion laughs") took minutes before its unknown key was reported.
#include "sensor/base/input_file.h"

#include <gtest/gtest.h>

#include <string>

#include "sensor/base/input_error.h"
#include "sensor/base/yaml_reader.h"
#include "tests/support/temp_dir.h"
#include "tests/support/text_file.h"

namespace camsim {
namespace {

std::string refusal(const std::filesystem::path& path, std::uintmax_t maxBytes) {
  try {
    readInputFile(path, "scene file", maxBytes);
  } catch (const InputError& e) {
    EXPECT_EQ(e.where().file, path.string());
    return e.message();
  }
  ADD_FAILURE() << path << " was read";
  return "";
}

TEST(InputFile, ReadsAFileAndRefusesDevicesDirectoriesAndOversizedFiles) {
  const test::TempDir dir;
  const std::filesystem::path file = dir.path() / "scene.yaml";
  test::writeFile(file, "name: x\n");
  EXPECT_EQ(readInputFile(file, "scene file"), "name: x\n");
  EXPECT_EQ(readInputFile(file, "scene file", 8), "name: x\n");  // exactly the limit
  EXPECT_NE(refusal(file, 7).find("scene file is larger than 7 bytes"), std::string::npos);
  EXPECT_NE(refusal("/dev/zero", kMaxInputFileBytes).find("not a regular file or a pipe"),
            std::string::npos);
  EXPECT_NE(refusal(dir.path(), kMaxInputFileBytes).find("it is a directory"), std::string::npos);
  EXPECT_NE(refusal(dir.path() / "missing.yaml", kMaxInputFileBytes).find("no such file"),
            std::string::npos);
}

// Nine levels of ten aliases each expand to 10^9 nodes; refused at once, at line 1.
TEST(YamlReader, AliasesThatExpandFarBeyondTheTextAreRefused) {
  std::string text = "a0: &a0 [x, x, x, x, x, x, x, x, x, x]\n";
  for (int level = 1; level <= 9; ++level) {
    const std::string prev = "*a" + std::to_string(level - 1);
    text += "a" + std::to_string(level) + ": &a" + std::to_string(level) + " [";
    for (int k = 0; k < 10; ++k) text += (k ? ", " : "") + prev;
    text += "]\n";
  }
  try {
    parseYaml(text, "bomb.yaml");
    ADD_FAILURE() << "parsed";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where().line, 1);
    EXPECT_NE(e.message().find("aliases"), std::string::npos) << e.what();
  }
  // Aliases used a few times, as scenes use them, still parse.
  EXPECT_NO_THROW(parseYaml("m: &m {type: diffuse}\nn: *m\no: *m\n", "ok.yaml"));
}

// Lists nested past yaml-cpp's depth guard: its message was "bad file" (found by probing).
TEST(YamlReader, NestingPastTheParsersLimitSaysSo) {
  const std::string text = "camera: " + std::string(5000, '[') + std::string(5000, ']') + "\n";
  try {
    parseYaml(text, "deep.yaml");
    ADD_FAILURE() << "parsed";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where().file, "deep.yaml");
    EXPECT_EQ(e.where().line, 1);
    EXPECT_NE(e.message().find("nested 500 levels deep, yaml-cpp's limit"), std::string::npos)
        << e.what();
  }
  EXPECT_NO_THROW(parseYaml("a: " + std::string(100, '[') + std::string(100, ']'), "ok.yaml"));
}

}  // namespace
}  // namespace camsim
