// Malformed glTF files: each is refused with an InputError naming the file and the JSON
// path of what is wrong (integrator/scene/gltf_validate.cpp, gltf_document.cpp,
// gltf_accessors.cpp, scene_loader_gltf.cpp, gltf_motion.cpp).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>

#include "integrator/scene/gltf_document.h"
#include "integrator/scene/scene_loader.h"
#include "sensor/base/input_error.h"
#include "sensor/spectra/cie.h"
#include "tests/integrator/scene/gltf_test_support.h"

namespace camsim {
namespace {

namespace fs = std::filesystem;

struct Refusal {
  std::string file, key, message;
};

Refusal refusal(const fs::path& file) {
  try {
    readGltf(file);
  } catch (const InputError& e) {
    return {e.where().file, e.key(), e.message()};
  }
  ADD_FAILURE() << file << " was accepted";
  return {};
}

fs::path scratch(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("camsim_gltf_errors_" + name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

std::string readBytes(const fs::path& f) {
  std::ifstream in(f, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST(GltfErrors, BoundsCheckingFilesNameTheirJsonPath) {
  const fs::path dir = test::kGltfData / "BoundsChecking";
  const struct {
    const char* file;
    const char* key;
    const char* says;
  } cases[] = {
      {"integer-out-of-bounds.gltf", "bufferViews[0].byteLength", "must be an integer"},
      {"invalid-buffer-index.gltf", "bufferViews[1].buffer", "must be an integer in [0, 0]"},
      // These two also have an empty buffers array, which is found first.
      {"invalid-buffer-view-index.gltf", "bufferViews[0].buffer",
       "refers to buffers, which is empty"},
      {"invalid-primitive-indices.gltf", "bufferViews[0].buffer",
       "refers to buffers, which is empty"},
  };
  for (const auto& c : cases) {
    const Refusal r = refusal(dir / c.file);
    EXPECT_EQ(r.file, (dir / c.file).string());
    EXPECT_EQ(r.key, c.key) << c.file << ": " << r.message;
    EXPECT_NE(r.message.find(c.says), std::string::npos) << c.file << ": " << r.message;
  }
}

TEST(GltfErrors, TruncatedGlb) {
  const std::string bytes = readBytes(test::kGltfData / "box01.glb");
  for (size_t keep : {size_t(3), size_t(19), bytes.size() / 2, bytes.size() - 1}) {
    const fs::path f = scratch("glb") / "cut.glb";
    test::writeText(f, bytes.substr(0, keep));
    const Refusal r = refusal(f);
    EXPECT_NE(r.message.find(keep < 4 ? "not valid JSON" : "truncated"), std::string::npos)
        << keep << ": " << r.message;
  }
}

TEST(GltfErrors, MissingBinAndMissingTexture) {
  const fs::path dir = scratch("missing");
  fs::copy_file(test::kGltfData / "Cube/Cube.gltf", dir / "Cube.gltf");
  Refusal r = refusal(dir / "Cube.gltf");
  EXPECT_EQ(r.key, "buffers[0].uri");
  EXPECT_NE(r.message.find("Cube.bin' not found"), std::string::npos) << r.message;
  fs::copy_file(test::kGltfData / "Cube/Cube.bin", dir / "Cube.bin");
  fs::copy_file(test::kGltfData / "Cube/Cube_BaseColor.png", dir / "Cube_BaseColor.png");
  r = refusal(dir / "Cube.gltf");
  EXPECT_EQ(r.key, "images[1].uri");
  EXPECT_NE(r.message.find("Cube_MetallicRoughness.png' not found"), std::string::npos)
      << r.message;
}

TEST(GltfErrors, CorruptImageIsRefused) {
  const fs::path dir = scratch("corrupt");
  fs::copy_file(test::kGltfData / "Cube/Cube.gltf", dir / "Cube.gltf");
  fs::copy_file(test::kGltfData / "Cube/Cube.bin", dir / "Cube.bin");
  fs::copy_file(test::kGltfData / "Cube/Cube_BaseColor.png", dir / "Cube_BaseColor.png");
  test::writeText(dir / "Cube_MetallicRoughness.png", "not a png");
  const Refusal r = refusal(dir / "Cube.gltf");
  EXPECT_EQ(r.key, "images[1]");
  EXPECT_NE(r.message.find("cannot decode image data"), std::string::npos) << r.message;
}

// One triangle whose POSITION data (and optionally indices) the test chooses.
fs::path triangleFile(const std::string& name, const std::vector<float>& positions,
                      const std::vector<std::uint16_t>& indices, const std::string& extra = "",
                      const std::string& node = R"({"mesh":0})") {
  test::GltfBuilder b;
  b.floats(positions, "VEC3");
  std::string prim = R"({"attributes":{"POSITION":0})";
  if (!indices.empty()) prim += ",\"indices\":" + std::to_string(b.u16(indices));
  prim += "}";
  const fs::path f = scratch(name) / (name + ".gltf");
  test::writeText(f, b.json(R"("meshes":[{"primitives":[)" + prim + R"(]}],"nodes":[)" + node +
                            R"(],"scenes":[{"nodes":[0]}])" + extra));
  return f;
}

TEST(GltfErrors, NanPositionAndIndexOutOfRange) {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  Refusal r = refusal(triangleFile("nan", {0, 0, 0, 1, nan, 0, 0, 1, 0}, {}));
  EXPECT_EQ(r.key, "accessors[0]");
  EXPECT_NE(r.message.find("element 1 is not finite"), std::string::npos) << r.message;
  r = refusal(triangleFile("index", {0, 0, 0, 1, 0, 0, 0, 1, 0}, {0, 1, 7}));
  EXPECT_EQ(r.key, "accessors[1]");
  EXPECT_NE(r.message.find("index 7 at element 2 is out of range: the primitive has 3 vertices"),
            std::string::npos)
      << r.message;
}

TEST(GltfErrors, InvalidJsonNamesTheLine) {
  const fs::path f = scratch("json") / "bad.gltf";
  test::writeText(f, "{\n  \"asset\": {\"version\": \"2.0\"},\n  \"nodes\": [,]\n}");
  try {
    readGltf(f);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.where().line, 3) << e.what();
    EXPECT_NE(std::string(e.what()).find("not valid JSON"), std::string::npos);
  }
}

TEST(GltfErrors, UnsupportedFeaturesAreRefusedClearly) {
  const std::vector<float> tri = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  auto viaScene = [](const fs::path& f) -> std::string {
    try {
      loadSceneFromText("camera: {position: [0, 0, 5], look_at: [0, 0, 0]}\ninclude:\n  - gltf: " +
                            f.string() + "\n",
                        "test.yaml", ".");
    } catch (const InputError& e) {
      return e.what();
    }
    return "accepted";
  };
  // A skin on a mesh node.
  EXPECT_NE(viaScene(triangleFile("skin", tri, {}, R"(,"skins":[{"joints":[0]}])",
                                  R"({"mesh":0,"skin":0})"))
                .find("nodes[0].skin': skinned meshes are not supported"),
            std::string::npos);
  // A required extension camsim does not read.
  EXPECT_NE(
      viaScene(
          triangleFile(
              "ext", tri, {},
              R"(,"extensionsRequired":["KHR_draco_mesh_compression"],"extensionsUsed":["KHR_draco_mesh_compression"])"))
          .find("requires KHR_draco_mesh_compression"),
      std::string::npos);
  // Morph targets.
  {
    test::GltfBuilder b;
    b.floats(tri, "VEC3");
    b.floats(tri, "VEC3");
    const fs::path f = scratch("morph") / "morph.gltf";
    test::writeText(
        f,
        b.json(
            R"("meshes":[{"primitives":[{"attributes":{"POSITION":0},"targets":[{"POSITION":1}]}]}],)"
            R"("nodes":[{"mesh":0}],"scenes":[{"nodes":[0]}])"));
    EXPECT_NE(viaScene(f).find("morph targets are not supported"), std::string::npos)
        << viaScene(f);
  }
  // A non-uniform animated scale, and an animated node under a non-uniform scale.
  {
    test::GltfBuilder b;
    b.floats(tri, "VEC3");
    const int t = b.floats({0, 1}, "SCALAR");
    const int s = b.floats({1, 1, 1, 2, 1, 1}, "VEC3");
    const int tr = b.floats({0, 0, 0, 1, 0, 0}, "VEC3");
    const std::string meshes = R"("meshes":[{"primitives":[{"attributes":{"POSITION":0}}]}],)";
    const std::string samplers = R"("samplers":[{"input":)" + std::to_string(t) + R"(,"output":)" +
                                 std::to_string(s) + R"(},{"input":)" + std::to_string(t) +
                                 R"(,"output":)" + std::to_string(tr) + "}]";
    fs::path f = scratch("scale") / "scale.gltf";
    test::writeText(
        f,
        b.json(meshes + R"("nodes":[{"mesh":0}],"scenes":[{"nodes":[0]}],"animations":[{)" +
               samplers + R"(,"channels":[{"sampler":0,"target":{"node":0,"path":"scale"}}]}])"));
    EXPECT_NE(viaScene(f).find("nodes[0].scale': an animated scale must be uniform"),
              std::string::npos)
        << viaScene(f);
    // An animated node under a static non-uniform scale: not a rigid motion.
    f = scratch("squashed") / "squashed.gltf";
    test::writeText(
        f,
        b.json(
            meshes +
            R"("nodes":[{"children":[1],"scale":[1,2,1]},{"mesh":0,"rotation":[0,0,0.6,0.8]}],)" +
            R"("scenes":[{"nodes":[0]}],"animations":[{)" + samplers +
            R"(,"channels":[{"sampler":1,"target":{"node":1,"path":"translation"}}]}])"));
    EXPECT_NE(viaScene(f).find("nodes[1]': an animated node's parents (and the include's "
                               "placement) must be rotations, translations and uniform"),
              std::string::npos)
        << viaScene(f);
  }
  // Lines are not surfaces.
  {
    test::GltfBuilder b;
    b.floats(tri, "VEC3");
    const fs::path f = scratch("lines") / "lines.gltf";
    test::writeText(f,
                    b.json(R"("meshes":[{"primitives":[{"attributes":{"POSITION":0},"mode":1}]}],)"
                           R"("nodes":[{"mesh":0}],"scenes":[{"nodes":[0]}])"));
    EXPECT_NE(viaScene(f).find("primitives[0].mode"), std::string::npos) << viaScene(f);
  }
}

// A view's byteStride below its accessor's element size would read overlapping elements
// (4-byte steps through 12-byte positions): refused, naming the view's byteStride.
TEST(GltfErrors, ByteStrideSmallerThanTheElementIsRefused) {
  test::GltfBuilder b;
  b.floats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3");
  std::string text = b.json(R"("meshes":[{"primitives":[{"attributes":{"POSITION":0}}]}],)"
                            R"("nodes":[{"mesh":0}],"scenes":[{"nodes":[0]}])");
  const std::string view = R"("byteLength":36})";
  ASSERT_NE(text.find(view), std::string::npos);
  text.replace(text.find(view), view.size(), R"("byteLength":36,"byteStride":4})");
  const fs::path f = scratch("stride") / "stride.gltf";
  test::writeText(f, text);
  const Refusal r = refusal(f);
  EXPECT_EQ(r.file, f.string());
  EXPECT_EQ(r.key, "bufferViews[0].byteStride") << r.message;
  EXPECT_NE(r.message.find("is 4 bytes, less than the 12-byte elements of accessors[0]"),
            std::string::npos)
      << r.message;
}

// A buffer whose data is shorter (or longer) than its byteLength: named as buffers[i] with
// both lengths, for a data URI and for a .bin file (not tinygltf's "Failed to decode 'uri'
// : data:…" without a JSON path).
TEST(GltfErrors, BufferShorterThanItsByteLengthNamesTheBuffer) {
  test::GltfBuilder b;
  b.floats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3");
  const std::string text = b.json(R"("meshes":[{"primitives":[{"attributes":{"POSITION":0}}]}],)"
                                  R"("nodes":[{"mesh":0}],"scenes":[{"nodes":[0]}])");
  const std::string length = R"("buffers":[{"byteLength":36,)";
  ASSERT_NE(text.find(length), std::string::npos);
  auto withLength = [&](const std::string& newLength, const std::string& uri) {
    std::string t = text;
    t.replace(t.find(length), length.size(), R"("buffers":[{"byteLength":)" + newLength + ",");
    if (!uri.empty()) {
      const size_t at = t.find("\"uri\":\"data:");
      t.replace(at, t.find('"', at + 7) + 1 - at, "\"uri\":\"" + uri + "\"");
    }
    return t;
  };
  const fs::path dir = scratch("short");
  test::writeText(dir / "short.gltf", withLength("40", ""));
  Refusal r = refusal(dir / "short.gltf");
  EXPECT_EQ(r.file, (dir / "short.gltf").string());
  EXPECT_EQ(r.key, "buffers[0]") << r.message;
  EXPECT_NE(
      r.message.find(
          "its data URI decodes to 36 bytes but its byteLength is 40: the buffer is truncated"),
      std::string::npos)
      << r.message;
  test::writeText(dir / "long.gltf", withLength("32", ""));
  r = refusal(dir / "long.gltf");
  EXPECT_EQ(r.key, "buffers[0]") << r.message;
  EXPECT_NE(r.message.find("36 bytes but its byteLength is 32"), std::string::npos) << r.message;
  test::writeText(dir / "tri.bin", std::string(20, '\0'));
  test::writeText(dir / "bin.gltf", withLength("36", "tri.bin"));
  r = refusal(dir / "bin.gltf");
  EXPECT_EQ(r.key, "buffers[0]") << r.message;
  EXPECT_NE(
      r.message.find("tri.bin' holds 20 bytes but its byteLength is 36: the buffer is truncated"),
      std::string::npos)
      << r.message;
  test::writeText(dir / "mime.gltf", withLength("36", "data:text/x-bin,AAAA"));
  r = refusal(dir / "mime.gltf");
  EXPECT_EQ(r.key, "buffers[0].uri") << r.message;
}

// Index accessors must be unsigned integers: float indices are a bad componentType, also
// when their view (sized for u16) is too short for floats (once reported as a count past
// the view's end).
TEST(GltfErrors, FloatIndicesAreABadComponentType) {
  for (const bool fits : {false, true}) {
    test::GltfBuilder b;
    b.floats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3");
    const int indices = fits ? b.floats({0, 1, 2}, "SCALAR") : b.u16({0, 1, 2});
    std::string text =
        b.json(R"("meshes":[{"primitives":[{"attributes":{"POSITION":0},"indices":)" +
               std::to_string(indices) + R"(}]}],"nodes":[{"mesh":0}],"scenes":[{"nodes":[0]}])");
    const std::string u16 = R"("componentType":5123)";
    if (!fits) text.replace(text.find(u16), u16.size(), R"("componentType":5126)");
    const fs::path f = scratch("float_indices") / "float_indices.gltf";
    test::writeText(f, text);
    const Refusal r = refusal(f);
    EXPECT_EQ(r.key, "accessors[1].componentType") << fits << ": " << r.message;
    EXPECT_NE(r.message.find("is FLOAT (5126) but meshes[0].primitives[0].indices needs "
                             "UNSIGNED_BYTE, UNSIGNED_SHORT or UNSIGNED_INT"),
              std::string::npos)
        << r.message;
  }
}

// COLOR_0 of unsigned bytes must be normalized; a bad KHR_texture_transform is named.
TEST(GltfErrors, BadColoursAndTextureTransformsAreNamed) {
  test::GltfBuilder b;
  b.floats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3");
  b.u8({255, 0, 0, 255, 0, 255, 0, 255, 0, 0, 255, 255}, "VEC4", false);
  const fs::path f = scratch("colours") / "colours.gltf";
  test::writeText(f,
                  b.json(R"("meshes":[{"primitives":[{"attributes":{"POSITION":0,"COLOR_0":1}}]}],)"
                         R"("nodes":[{"mesh":0}],"scenes":[{"nodes":[0]}])"));
  Refusal r = refusal(f);
  EXPECT_EQ(r.key, "accessors[1].normalized") << r.message;
  const fs::path g = scratch("transform") / "transform.gltf";
  test::writeText(g,
                  test::GltfBuilder().json(
                      R"("textures":[{}],"materials":[{"pbrMetallicRoughness":{"baseColorTexture":)"
                      R"({"index":0,"extensions":{"KHR_texture_transform":{"offset":[1]}}}}}])"));
  r = refusal(g);
  EXPECT_EQ(r.key,
            "materials[0].pbrMetallicRoughness.baseColorTexture.extensions.KHR_texture_transform."
            "offset")
      << r.message;
}

// Found by fuzz_gltf: a number beyond double's range made nlohmann-json throw out_of_range,
// which escaped as another exception type.
TEST(GltfErrors, NumberBeyondDoubleRangeIsAnInputError) {
  const fs::path f = scratch("overflow") / "overflow.gltf";
  test::writeText(f, R"({"asset":{"version":"2.0"},"nodes":[{"translation":[1e3051210,0,0]}]})");
  const Refusal r = refusal(f);
  EXPECT_NE(r.message.find("not valid JSON"), std::string::npos) << r.message;
}

// Found by probing the command line: an emissive factor of 1e38 (or KHR_materials_emissive_
// strength 1e38) loaded, and its float spectrum overflowed: every pixel NaN, exit 0. Now the
// emitter's luminance is held to the scene format's 1e15 cd/m², a negative factor refused,
// both named by JSON path; a bright but finite one (1e12 cd/m²) still loads.
TEST(GltfErrors, EmissionBeyondTheSceneLimitIsRefused) {
  const auto load = [](const std::string& name, const std::string& material,
                       const std::string& option = "") {
    test::GltfBuilder b;
    b.floats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3");
    const fs::path dir = scratch(name);
    test::writeText(
        dir / "tri.gltf",
        b.json(R"("meshes":[{"primitives":[{"attributes":{"POSITION":0},"material":0}]}],)"
               R"("nodes":[{"mesh":0}],"scenes":[{"nodes":[0]}],"materials":[)" +
               material + "]"));
    return loadSceneFromText(
        "camera: {position: [0, 0, 5], look_at: [0, 0, 0], resolution: [8, 8]}\n"
        "include:\n  - gltf: tri.gltf\n" +
            option,
        "emit.yaml", dir);
  };
  const struct {
    const char* material;
    const char* key;
  } cases[] = {
      {R"({"emissiveFactor":[1e38,1e38,1e38]})", "materials[0].emissiveFactor"},
      {R"({"emissiveFactor":[1,1,1],"extensions":{"KHR_materials_emissive_strength":)"
       R"({"emissiveStrength":1e38}}})",
       "materials[0].extensions.KHR_materials_emissive_strength.emissiveStrength"},
      {R"({"emissiveFactor":[1,-1,1]})", "materials[0].emissiveFactor[1]"},
  };
  int k = 0;
  for (const auto& c : cases) {
    SCOPED_TRACE(c.material);
    try {
      load("emit" + std::to_string(k++), c.material);
      ADD_FAILURE() << "loaded";
    } catch (const InputError& e) {
      EXPECT_EQ(e.key(), c.key) << e.what();
      EXPECT_EQ(fs::path(e.where().file).filename(), "tri.gltf") << e.what();
    }
  }
  const SceneDescription bright = load(
      "emit_ok", R"({"emissiveFactor":[1,1,1],"extensions":{"KHR_materials_emissive_strength":)"
                 R"({"emissiveStrength":1e10}}})");
  ASSERT_EQ(bright.shapes.size(), 1u);
  EXPECT_TRUE(bright.shapes[0].emission.has_value());
  // A strength of 1e300 against an emissive_luminance of 1e-300 is 1 cd/m²: the colour's
  // shape is taken from the normalised factor (from e itself its float spectrum overflowed
  // and a light's weight went negative: a failed check, exit 134).
  const SceneDescription balanced =
      load("emit_balanced",
           R"({"emissiveFactor":[1,0.5,0.25],"extensions":{"KHR_materials_emissive_strength":)"
           R"({"emissiveStrength":1e300}}})",
           "    emissive_luminance: 1e-300\n");
  ASSERT_EQ(balanced.shapes.size(), 1u);
  ASSERT_TRUE(balanced.shapes[0].emission.has_value());
  const double y = luminance(balanced.shapes[0].emission->radiance);
  EXPECT_NEAR(y, 1e-300 * 1e300 * (0.2126 + 0.7152 * 0.5 + 0.0722 * 0.25), 1e-3) << y;
}

}  // namespace
}  // namespace camsim
