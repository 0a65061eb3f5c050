// Material inputs that may vary over a surface (docs/scene-format.md, "Textures"):
//
// | form                                                    | reflectance | roughness / fraction | normal map |
// |---------------------------------------------------------|-------------|-----------|------------|
// | a spectrum (scene_spectra.h) / a number                 | constant    | constant (≥ 0, ≤ 1000 / in [0, 1]) | — |
// | {texture: FILE, encoding: E, channel: C, scale: [su, sv], offset: [ou, ov]} | image | image | image (RGB, raw; no encoding, no channel) |
// | {checkerboard: {a: A, b: B, checks: N}, scale, offset}  | spectra A, B | numbers A, B | — |
//
// | key          | unit | default | meaning |
// |--------------|------|---------|---------|
// | texture      | —    | —       | .png or .exr, relative to the scene file |
// | encoding     | —    | reflectance: png srgb, exr linear; roughness, fraction: raw | srgb, linear, raw |
// | channel      | —    | −1 (grey, or the mean of R, G, B) | scalar maps: 0 R, 1 G, 2 B, 3 A (image_texture.h) |
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
#include <vector>

#include "integrator/scene/scene_loader_parts.h"
#include "integrator/textures/image_texture.h"
#include "sensor/base/file_status.h"

namespace camsim {
namespace {

constexpr double kMaxRoughness = 1e3;

// The largest constant of a scalar input.
double maxScalar(TextureUse use) {
  return use == TextureUse::kFraction ? 1.0 : kMaxRoughness;
}
bool scalar(TextureUse use) {
  return use == TextureUse::kRoughness || use == TextureUse::kFraction;
}

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
  if (use != TextureUse::kReflectance) t.encoding = TextureEncoding::kRaw;
  std::vector<std::string> known = {"texture", "scale", "offset"};
  if (use != TextureUse::kNormalMap) {  // a normal map's numbers are never decoded
    known.push_back("encoding");
    if (auto e = map.find("encoding")) t.encoding = e->choice<TextureEncoding>("encoding");
  }
  if (scalar(use)) {
    known.push_back("channel");
    if (auto c = map.find("channel")) t.channel = static_cast<int>(c->integer(0, 3));
  } else if (auto c = map.find("channel")) {
    c->fail("'channel' selects one channel of a scalar map (roughness, metallic), not of " +
            std::string(use == TextureUse::kNormalMap ? "a normal map" : "a colour texture"));
  }
  if (!isRegularFile(t.file)) file.fail("texture file '" + t.file.string() + "' not found");
  try {
    t.image = std::make_shared<const TextureImage>(loadTextureImage(t.file, t.encoding));
  } catch (const InputError& e) {
    file.fail("texture file '" + t.file.string() + "': " + e.message());
  }
  if (use == TextureUse::kNormalMap && t.image->channels != 3)
    file.fail("texture file '" + t.file.string() +
              "': a normal map needs R, G and B channels (it has one grey channel)");
  parseUvTransform(map, t);
  map.finish(known);
  return t;
}

TextureDescription parseCheckerboard(YamlMap& map, TextureUse use, const TableSearch& search) {
  TextureDescription t;
  t.kind = TextureDescription::Kind::kCheckerboard;
  YamlMap board(map.require("checkerboard"));
  auto value = [&](const YamlValue& v) {
    if (scalar(use)) return Spectrum::constant(v.number(0.0, maxScalar(use)));
    return parseSpectrum(v, SpectrumUse::kReflectance, search);
  };
  if (auto a = board.find("a")) t.checkerA = value(*a);
  if (auto b = board.find("b")) t.checkerB = value(*b);
  if (auto n = board.find("checks")) t.checks = positiveFloat(*n, n->number(0.0, 1e6, true));
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
    if (use == TextureUse::kNormalMap) v.fail("expected {texture: FILE, …} (an RGB normal map)");
    if (map.has("checkerboard")) return parseCheckerboard(map, use, search);
    if (use == TextureUse::kReflectance && !map.has("rgb") && !map.has("csv") &&
        !map.has("blackbody") && !map.has("illuminant"))
      v.fail(
          "expected a number in [0, 1], {rgb: […]}, {csv: …}, {texture: FILE, …} or {checkerboard: "
          "{…}}");
  }
  if (use == TextureUse::kNormalMap) v.fail("expected {texture: FILE, …} (an RGB normal map)");
  if (scalar(use)) {
    if (!v.isScalar())
      v.fail(std::string(use == TextureUse::kFraction ? "expected a number in [0, 1]"
                                                      : "expected a number ≥ 0") +
             ", {texture: FILE, …} or {checkerboard: {…}}");
    return TextureDescription::constant(v.number(0.0, maxScalar(use)));
  }
  TextureDescription t;
  t.value = parseSpectrum(v, SpectrumUse::kReflectance, search);
  return t;
}

}  // namespace camsim
