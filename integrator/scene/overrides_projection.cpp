// The projection override (overrides_projection.h): the scene loader reads the block on a
// camera-only probe scene, so the keys, ranges and messages are camera.projection's own.
#include "integrator/scene/overrides_projection.h"

#include <algorithm>
#include <charconv>
#include <cstdio>
#include <string>
#include <utility>

#include "integrator/camera/projection.h"
#include "integrator/scene/scene_loader.h"
#include "sensor/base/yaml_reader.h"
#include "sensor/io/json_writer.h"

#include "sensor/base/format.h"

namespace camsim {
namespace {

const char* const kKey = "camera.projection";

// The scene the loader reads for `projection` (YAML text, any number of lines): a camera
// with that block and one sphere. Its errors keep the loader's key, at `where` (the probe's
// own lines and columns would mean nothing to the user).
SceneDescription probe(std::string_view projection, const SourceLocation& where) {
  std::string block;
  std::size_t start = 0;
  while (start <= projection.size()) {
    const std::size_t end = std::min(projection.find('\n', start), projection.size());
    block += "    " + std::string(projection.substr(start, end - start)) + "\n";
    start = end + 1;
  }
  try {
    return loadSceneFromText(
        "camera:\n  position: [0, 0, 0]\n  look_at: [0, 0, -1]\n"
        "  projection:\n" +
            block +
            "materials: {m: {type: diffuse}}\nshapes: [{type: sphere, "
            "centre: [0, 0, 0], radius: 1, material: m}]\n",
        "<override>", ".");
  } catch (const InputError& e) {
    throw InputError(where, e.key().empty() ? kKey : e.key(), e.message());
  }
}

}  // namespace

ProjectionOverride readProjectionOverride(std::string_view text, const SourceLocation& where) {
  probe(text, where);  // every check is the loader's; what follows only copies the values
  ProjectionOverride p;
  YamlMap map(parseYaml(std::string(text), "<override>"));
  for (const std::string& key : map.keys()) {
    const YamlValue value = *map.find(key);
    if (key == "model")
      p.model = value.string();
    else
      p.values.emplace_back(key, value.number());
  }
  return p;
}

std::string projectionOverrideText(const ProjectionOverride& p) {
  std::string out = "{\"model\": " + JsonObject::quoted(p.model);
  for (const auto& [key, value] : p.values)
    out += ", " + JsonObject::quoted(key) + ": " + formatShortest(value);
  return out + "}";
}

void setProjection(SceneDescription& d, const ProjectionOverride& p, const SourceLocation& where) {
  const SceneDescription checked = probe(projectionOverrideText(p), where);
  const PhysicalCameraParams& c = checked.camera;
  // The loader's rule, which the probe (an aplanatic pupil) cannot see.
  if (c.projection.model != ProjectionModel::kOpenCv && d.camera.pupil == LensPupil::kFlat)
    throw InputError(where, std::string(kKey) + ".model",
                     "model '" + p.model +
                         "' with the scene's camera.aperture.pupil: flat: the flat pupil applies "
                         "to the opencv model only (the pupil of the fisheye and omnidirectional "
                         "models turns with the field)");
  // And the exports' (parseExports): found by probing, a fisheye override wrote BOP's cam_K
  // and KITTI's P2 as the pinhole the image was not (the same scene file is refused).
  if (const std::string problem = pinholeExportProblem(d, c.projection); !problem.empty())
    throw InputError(where, kKey, "model '" + p.model + "': " + problem);
  if (!c.intrinsicsFromLens)
    if (const std::string problem = imagedNothing(c.projection, d.camera.resolution);
        !problem.empty())
      throw InputError(where, kKey, problem);
  d.camera.projection = c.projection;
  d.camera.intrinsicsFromLens = c.intrinsicsFromLens;
}

}  // namespace camsim
