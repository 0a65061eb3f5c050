// Material inputs that may vary over a surface (docs/scene-format.md, "Textures"):
//
// | form                                                    | reflectance | roughness |
// |---------------------------------------------------------|-------------|-----------|
// | a spectrum (scene_spectra.h) / a number ≥ 0             | constant    | constant  |
// | {texture: FILE, encoding: E, scale: [su, sv], offset: [ou, ov]} | image | image |
// | {checkerboard: {a: A, b: B, checks: N}, scale, offset}  | spectra A, B | numbers A, B |
//
// | key          | unit | default | meaning |
// |--------------|------|---------|---------|
// | texture      | —    | —       | .png or .exr, relative to the scene file |
// | encoding     | —    | reflectance: png srgb, exr linear; roughness: raw | srgb, linear, raw |
// | scale        | —    | [1, 1]  | uv' = uv · scale + offset (a number: both) |
// | offset       | —    | [0, 0]  | |
// | checks       | —    | 8       | squares per unit of u and v, in (0, 10⁶] |
// | a, b         | —    | 0.8, 0.2 | reflectance spectra in [0, 1] / roughness numbers in [0, 1000]
// |
//
// The image is read here, once: a bad file (type, channels) is reported at the scene key,
// and the description carries the decoded texels to the renderer.
#include <cmath>
#include <string>

#include "integrator/scene/scene_loader_parts.h"
#include "integrator/textures/image_texture.h"
#include "sensor/base/file_status.h"

namespace camsim {
namespace {

constexpr double kMaxRoughness = 1e3;

// [x, y] (or one number for both), finite and within single precision.
glm::vec2 parseVec2(const YamlValue& v) {
  if (v.isScalar()) {
    const float s = static_cast<float>(v.number(-1e30, 1e30));
    return {s, s};
  }
  const std::vector<double> xy = v.numbers();
  if (xy.size() != 2) v.fail("expected [u, v] (two numbers) or one number");
  for (double d : xy)
    if (std::fabs(d) > 1e30) v.fail("expected values within ±1e30");
  return {static_cast<float>(xy[0]), static_cast<float>(xy[1])};
}

void parseUvTransform(YamlMap& map, TextureDescription& t) {
  if (auto s = map.find("scale")) t.uvScale = parseVec2(*s);
  if (auto o = map.find("offset")) t.uvOffset = parseVec2(*o);
}

TextureDescription parseImage(YamlMap& map, TextureUse use, const std::filesystem::path& baseDir) {
  TextureDescription t;
  t.kind = TextureDescription::Kind::kImage;
  const YamlValue file = map.require("texture");
  t.file = file.string();
  if (t.file.is_relative()) t.file = baseDir / t.file;
  try {
    t.encoding = defaultTextureEncoding(t.file);  // checks the file type
  } catch (const InputError& e) {
    file.fail(e.message());
  }
  if (use == TextureUse::kRoughness) t.encoding = TextureEncoding::kRaw;
  if (auto e = map.find("encoding"))
    t.encoding = e->choice<TextureEncoding>("encoding", {{"srgb", TextureEncoding::kSrgb},
                                                         {"linear", TextureEncoding::kLinear},
                                                         {"raw", TextureEncoding::kRaw}});
  if (!isRegularFile(t.file)) file.fail("texture file '" + t.file.string() + "' not found");
  try {
    t.image = std::make_shared<const TextureImage>(loadTextureImage(t.file, t.encoding));
  } catch (const InputError& e) {
    file.fail("texture file '" + t.file.string() + "': " + e.message());
  }
  parseUvTransform(map, t);
  map.finish({"texture", "encoding", "scale", "offset"});
  return t;
}

TextureDescription parseCheckerboard(YamlMap& map, TextureUse use, const TableSearch& search) {
  TextureDescription t;
  t.kind = TextureDescription::Kind::kCheckerboard;
  YamlMap board(map.require("checkerboard"));
  auto value = [&](const YamlValue& v) {
    if (use == TextureUse::kRoughness) return Spectrum::constant(v.number(0.0, kMaxRoughness));
    return parseSpectrum(v, SpectrumUse::kReflectance, search);
  };
  if (auto a = board.find("a")) t.checkerA = value(*a);
  if (auto b = board.find("b")) t.checkerB = value(*b);
  if (auto n = board.find("checks")) t.checks = static_cast<float>(n->number(0.0, 1e6, true));
  board.finish({"a", "b", "checks"});
  parseUvTransform(map, t);
  map.finish({"checkerboard", "scale", "offset"});
  return t;
}

}  // namespace

TextureDescription parseTexture(const YamlValue& v, TextureUse use, const TableSearch& search,
                                const std::filesystem::path& baseDir) {
  if (v.isMap()) {
    YamlMap map(v);
    if (map.has("texture")) {
      TextureDescription t = parseImage(map, use, baseDir);
      search.noteRead(t.file);
      return t;
    }
    if (map.has("checkerboard")) return parseCheckerboard(map, use, search);
    if (use == TextureUse::kReflectance && !map.has("rgb") && !map.has("csv") &&
        !map.has("blackbody") && !map.has("illuminant"))
      v.fail(
          "expected a number in [0, 1], {rgb: […]}, {csv: …}, {texture: FILE, …} or {checkerboard: "
          "{…}}");
  }
  if (use == TextureUse::kRoughness) {
    if (!v.isScalar()) v.fail("expected a number ≥ 0, {texture: FILE, …} or {checkerboard: {…}}");
    return TextureDescription::constant(v.number(0.0, kMaxRoughness));
  }
  TextureDescription t;
  t.value = parseSpectrum(v, SpectrumUse::kReflectance, search);
  return t;
}

}  // namespace camsim
