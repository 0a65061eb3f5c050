#include "integrator/scene/scene_loader.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <map>
#include <optional>
#include <set>

#include <glm/geometric.hpp>

#include "integrator/scene/gltf_convert.h"
#include "integrator/scene/scene_ids.h"
#include "integrator/scene/scene_loader_parts.h"
#include "integrator/scene/scene_spectra.h"
#include "sensor/base/file_status.h"
#include "sensor/base/fnv1a.h"
#include "sensor/base/format.h"
#include "sensor/base/input_file.h"
#include "sensor/base/yaml_reader.h"
#include "sensor/spectra/cie.h"
#include "sensor/spectra/spectral_data.h"

namespace camsim {

// Computed from the single-precision positions the renderer uses.
double meshArea2(const MeshData& mesh) {
  double area = 0.0;
  for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
    const glm::dvec3 a = mesh.positions[mesh.indices[t]], b = mesh.positions[mesh.indices[t + 1]],
                     c = mesh.positions[mesh.indices[t + 2]];
    area += glm::length(glm::cross(b - a, c - a));
  }
  return area;
}

namespace {

struct Context {
  std::filesystem::path baseDir;
  TableSearch search;
  std::map<std::string, int> materialIndex;                     // the scene's `materials:`
  ImportedMaterials imported;                                   // those of mesh files (OBJ .mtl)
  const std::vector<MaterialDescription>* materials = nullptr;  // the scene's, parsed first
  glm::dvec3 origin{0.0};  // render-space origin (SceneDescription::renderOrigin)
};

FrameSequence parseFrames(YamlMap map) {
  FrameSequence f;
  if (auto v = map.find("count")) f.count = static_cast<int>(v->integer(1, 100000));
  if (auto v = map.find("rate_hz")) f.rateHz = v->number(1e-3, 1e6);
  if (auto v = map.find("first")) f.first = static_cast<int>(v->integer(0, 10000000));
  if (auto v = map.find("shutter_angle_deg"))
    f.shutterAngleDeg = v->number(setting_ranges::kMinShutterAngleDeg, 360.0);
  map.finish({"count", "rate_hz", "first", "shutter_angle_deg"});
  return f;
}

// Whether some shape has a `class:` (the amodal aov's masks are of those shapes).
bool hasLabelledShape(const SceneDescription& scene) {
  return std::any_of(scene.shapes.begin(), scene.shapes.end(),
                     [](const ShapeDescription& s) { return !s.className.empty(); });
}

// `exports:` — a list of layouts (ExportFormat), each once. bop and kitti need a camera that
// a pinhole matrix describes (the opencv model without distortion) and add the AOVs their
// files are made of: depth (BOP's depth/) and, when a shape is labelled, amodal (the masks).
void parseExports(const YamlValue& list, SceneDescription& scene) {
  scene.keyPlaces["exports"] = list.where();
  for (const YamlValue& item : list.items()) {
    const ExportFormat f = item.choice<ExportFormat>("export");
    if (scene.exportsTo(f))
      item.fail(std::string("export '") + exportFormatName(f) + "' is listed twice");
    scene.exports.push_back(f);
  }
  if (const std::string problem = pinholeExportProblem(scene, scene.camera.projection);
      !problem.empty())
    list.fail(problem);
  // The aovs their files are made of: BOP's depth/ and, for both, the masks (BOP's mask/,
  // mask_visib/ and counts; KITTI's `occluded`) — amodal only with a labelled shape.
  std::vector<Aov>& aovs = scene.render.aovs;
  const auto add = [&aovs](Aov a) {
    if (std::find(aovs.begin(), aovs.end(), a) == aovs.end()) aovs.push_back(a);
  };
  if (scene.exportsTo(ExportFormat::kBop)) add(Aov::kDepth);
  if (!scene.exports.empty() && hasLabelledShape(scene)) add(Aov::kAmodal);
}

RenderSettings parseRender(YamlMap map) {
  RenderSettings r;
  if (auto v = map.find("sampler")) r.sampler = v->choice<SamplerKind>("sampler");
  if (auto v = map.find("spp"))
    r.spp = static_cast<int>(v->integer(setting_ranges::kSpp.lo, setting_ranges::kSpp.hi));
  if (auto v = map.find("seed"))
    r.seed =
        static_cast<std::uint64_t>(v->integer(setting_ranges::kSeed.lo, setting_ranges::kSeed.hi));
  if (auto v = map.find("max_depth"))
    r.maxDepth = static_cast<int>(v->integer(0, SceneLimits::kMaxDepth));
  if (auto v = map.find("rr_depth"))
    r.rrDepth = static_cast<int>(v->integer(1, SceneLimits::kMaxDepth));
  namespace R = setting_ranges;
  if (auto v = map.find("target_error"))
    r.targetError = v->number(R::kTargetError.lo, R::kTargetError.hi, R::kTargetError.loOpen);
  if (auto v = map.find("time_limit_s"))
    r.timeLimitS = v->number(R::kTimeLimitS.lo, R::kTimeLimitS.hi, R::kTimeLimitS.loOpen);
  if (auto v = map.find("max_spp")) {
    r.maxSpp = static_cast<int>(v->integer(R::kSpp.lo, R::kSpp.hi));
    if (r.maxSpp < r.spp)
      v->fail("max_spp " + std::to_string(r.maxSpp) + " is below spp " + std::to_string(r.spp));
  }
  if (auto v = map.find("adaptive_threshold"))
    r.adaptiveThreshold =
        v->number(R::kAdaptiveThreshold.lo, R::kAdaptiveThreshold.hi, R::kAdaptiveThreshold.loOpen);
  if (auto v = map.find("adaptive_min_spp")) {
    r.adaptiveMinSpp = static_cast<int>(v->integer(R::kAdaptiveMinSpp.lo, R::kAdaptiveMinSpp.hi));
    if (r.adaptiveMinSpp % 2 != 0)
      v->fail("adaptive_min_spp " + std::to_string(r.adaptiveMinSpp) +
              " is odd: the convergence checks compare a pixel's two equal halves of samples");
  }
  if (auto v = map.find("guiding")) {
    // true/false, or the override's 0/1 (setting_ranges::kGuiding: a dataset item sets it so).
    const std::string text = v->isScalar() ? v->string() : "";
    r.guiding = text == "0" || text == "1" ? text == "1" : v->boolean();
  }
  if (auto v = map.find("spectral_control_variate")) r.spectralControlVariate = v->boolean();
  if (auto v = map.find("aovs")) {
    for (const YamlValue& item : v->items()) {
      const Aov aov = item.choice<Aov>("aov");
      if (std::find(r.aovs.begin(), r.aovs.end(), aov) != r.aovs.end())
        item.fail(std::string("aov '") + aovName(aov) + "' is listed twice");
      r.aovs.push_back(aov);
    }
  }
  map.finish({"sampler", "spp", "seed", "max_depth", "rr_depth", "aovs", "target_error",
              "time_limit_s", "max_spp", "adaptive_threshold", "adaptive_min_spp", "guiding",
              "spectral_control_variate"});
  return r;
}

EmissionDescription parseEmission(YamlMap map, const Context& ctx) {
  EmissionDescription e;
  const auto spectrum = map.find("spectrum");
  const Spectrum shape = spectrum ? parseSpectrum(*spectrum, SpectrumUse::kEmission, ctx.search)
                                  : cieIlluminant("D65");
  const auto lum = map.find("luminance");
  const auto scale = map.find("scale");
  if (lum && scale) scale->fail("give either luminance (cd/m²) or scale, not both");
  if (lum) {
    const double target = lum->number(0.0, SceneLimits::kMaxLuminance);
    const double shapeLuminance = luminance(shape);
    if (target > 0.0 && !(shapeLuminance > 0.0))
      (spectrum ? *spectrum : *lum)
          .fail("this spectrum has no visible power, so it cannot have a luminance");
    e.radiance = target > 0.0 ? shape * (target / shapeLuminance) : Spectrum::constant(0.0);
  } else if (scale) {
    e.radiance = shape * scale->number(0.0, 1e30);
  } else {
    map.self().fail(
        "emission needs 'luminance' (cd/m²) or 'scale' (W·m⁻²·sr⁻¹·nm⁻¹ per spectrum unit)");
  }
  if (!std::isfinite(e.radiance.maxValue()))
    (lum ? *lum : *scale).fail("the radiance exceeds the single-precision range");
  if (auto t = map.find("two_sided")) e.twoSided = t->boolean();
  map.finish({"spectrum", "luminance", "scale", "two_sided"});
  return e;
}

std::vector<std::uint32_t> parseFaces(const YamlValue& faces, size_t vertexCount) {
  std::vector<std::uint32_t> indices;
  for (const YamlValue& face : faces.items()) {
    const std::vector<YamlValue> idx = face.items();
    if (idx.size() < 3) face.fail("a face needs at least 3 vertex indices");
    std::vector<std::uint32_t> poly;
    for (const YamlValue& i : idx)
      poly.push_back(
          static_cast<std::uint32_t>(i.integer(0, static_cast<std::int64_t>(vertexCount) - 1)));
    for (size_t k = 1; k + 1 < poly.size(); ++k)
      indices.insert(indices.end(), {poly[0], poly[k], poly[k + 1]});
    if (indices.size() / 3 > static_cast<size_t>(SceneLimits::kMaxTrianglesInline))
      faces.fail("too many triangles for an inline mesh: use a mesh file");
  }
  return indices;
}

// The spacing of single-precision coordinates d metres from render space's origin (m).
double floatSpacingAt(double d) {
  const float f = static_cast<float>(d);
  return static_cast<double>(std::nextafter(f, INFINITY)) - static_cast<double>(f);
}

void checkMesh(const YamlValue& where, const MeshData& mesh) {
  if (mesh.indices.empty()) where.fail("mesh has no triangles");
  if (!(meshArea2(mesh) > 0.0)) where.fail("mesh has zero area");
}

}  // namespace

void parseShapeClass(const YamlValue& c, ShapeDescription& s) {
  // An integer in [1, 2^24] is the class number itself (exact in the float class.id
  // channel); any other text names a class that scene_ids.h numbers. Text that reads as
  // another number (1e3, 2.0, -3) is refused: found by probing, `class: 1e3` became a class
  // *named* "1e3" with number 1.
  s.className = c.string();
  s.classNumber.reset();
  const bool digits =
      !s.className.empty() && s.className.find_first_not_of("0123456789") == std::string::npos;
  if (digits) s.classNumber = static_cast<std::uint32_t>(c.integer(1, kMaxClassNumber));
  if (s.className.empty()) c.fail("class must be a non-empty name or an integer >= 1");
  double number = 0.0;
  const char* end = s.className.data() + s.className.size();
  const auto [ptr, ec] = std::from_chars(s.className.data(), end, number);
  if (!digits && ec == std::errc() && ptr == end &&
      s.className.find_first_of("0123456789") != std::string::npos)
    c.fail("class '" + s.className + "' reads as a number: give an integer in [1, " +
           std::to_string(kMaxClassNumber) + "], or a name");
}

namespace {

// Named classes are numbered after the largest integer class (scene_ids.h): all of them
// must stay within kMaxClassNumber (found by probing: after class 4294967295 the next name
// wrapped to 0, the background).
void checkClassNumbers(const SceneDescription& scene, const YamlValue& shapes) {
  std::uint64_t largest = 0;
  std::set<std::string> names;
  for (const ShapeDescription& s : scene.shapes) {
    if (s.classNumber) largest = std::max<std::uint64_t>(largest, *s.classNumber);
    if (!s.className.empty() && !s.classNumber) names.insert(s.className);
  }
  if (largest + names.size() > kMaxClassNumber)
    shapes.fail("the named classes are numbered after the largest integer class, " +
                std::to_string(largest) + ", and " + std::to_string(names.size()) +
                " of them pass " + std::to_string(kMaxClassNumber) +
                " (class.id is float, exact to 2^24): use smaller integer classes");
}

}  // namespace

namespace {

// One shape entry → its ShapeDescription, one per material when a mesh file brings its own
// (scene_loader_mtl.cpp), and each of those once per item of its `instances:` list.
void parseShape(YamlMap map, size_t index, Context& ctx, SceneDescription& scene,
                std::vector<ShapeDescription>& out) {
  ShapeDescription s;
  s.label = "shapes[" + std::to_string(index) + "]";
  s.key = s.label;
  s.where = map.self().where();
  if (auto n = map.find("name")) s.label = n->string();
  const YamlValue type = map.require("type");
  const std::string t = type.string();
  std::vector<std::string> known = {"type", "name", "class", "material", "emission", "motion"};
  if (auto c = map.find("class")) parseShapeClass(*c, s);
  const std::optional<YamlValue> instances = map.find("instances");
  if (instances && t != "mesh") instances->fail("instances: only a mesh shape can be instanced");
  if (auto m = map.find("motion")) {
    if (instances) m->fail("a shape with instances cannot move: give each instance its motion");
    // Keyframes carry the world position, shifted into render space (in double); the
    // geometry itself is then in object space.
    s.motion = parseMotion(*m, false, ctx.origin);
  }
  // Render-space position of a point given in the scene file (instances: object space).
  const glm::dvec3 shift = s.motion.empty() && !instances ? ctx.origin : glm::dvec3(0.0);
  auto point = [&](const YamlValue& where, const glm::dvec3& v) {
    return toPoint(where, v - shift);
  };
  std::optional<YamlValue> meshFile;  // a mesh file's `file:` and its path
  std::filesystem::path meshPath;
  if (t == "sphere") {
    s.kind = ShapeDescription::Kind::kSphere;
    const YamlValue centre = map.require("centre");
    s.centre = point(centre, centre.vec3());
    const YamlValue radius = map.require("radius");
    s.radius = static_cast<float>(radius.number(SceneLimits::kMinSphereRadius, 1e12));
    known.insert(known.end(), {"centre", "radius"});
  } else if (t == "rectangle") {
    const YamlValue cv = map.require("corner");
    const glm::dvec3 corner = cv.vec3();
    // Look both edges up before requiring either, so that a missing edge_u is not taken
    // for a misspelling of edge_v.
    map.find("edge_u");
    map.find("edge_v");
    const YamlValue eu = map.require("edge_u"), ev = map.require("edge_v");
    const glm::dvec3 u = eu.vec3(), v = ev.vec3();
    s.mesh.positions = {point(cv, corner), point(eu, corner + u), point(ev, corner + u + v),
                        point(ev, corner + v)};
    s.mesh.indices = {0, 1, 2, 0, 2, 3};
    s.mesh.uvs = {{0.0f, 0.0f}, {1.0f, 0.0f}, {1.0f, 1.0f}, {0.0f, 1.0f}};  // corner, +u, +u+v, +v
    s.objectFromModel[3] = glm::dvec4(-shift, 1.0);  // the model: the corners as written
    if (!(glm::length(glm::cross(u, v)) > 0.0))
      ev.fail("edge_u and edge_v must span a non-zero area");
    if (!(meshArea2(s.mesh) > 0.0))  // render space is centred on the camera, in float
      cv.fail("the rectangle is too small to be stored " +
              formatNumber(glm::length(corner - shift)) +
              " m from the camera, where single-precision coordinates are " +
              formatNumber(floatSpacingAt(glm::length(corner - shift))) + " m apart");
    known.insert(known.end(), {"corner", "edge_u", "edge_v"});
  } else if (t == "mesh") {
    const auto file = map.find("file");
    const auto vertices = map.find("vertices");
    if (file && vertices) vertices->fail("give either 'file' or 'vertices', not both");
    if (file) {
      std::filesystem::path p(file->string());
      if (p.is_relative()) p = ctx.baseDir / p;
      if (!isRegularFile(p)) file->fail("mesh file '" + p.string() + "' not found");
      ctx.search.noteRead(p);
      MeshPlacement placement;  // applied in double as the file is read
      if (auto sc = map.find("scale")) placement.scale = sc->number(0.0, 1e12, true);
      if (auto tr = map.find("translate")) {
        placement.offset = tr->vec3();
        // Checked before the file is read: past the range float positions collapse, and
        // the mesh was refused as of zero area.
        (void)point(*tr, placement.offset);
      }
      placement.offset -= shift;
      try {
        s.mesh = readMeshFile(p, placement);
      } catch (const InputError& e) {
        file->failInNamedFile(e);
      }
      checkMesh(*file, s.mesh);
      // The model frame (object_poses.h): the file's vertices × scale; translate is pose.
      s.objectFromModel[3] = glm::dvec4(placement.offset, 1.0);
      meshFile = file;
      meshPath = p;
    } else if (vertices) {
      for (const YamlValue& v : vertices->items()) s.mesh.positions.push_back(point(v, v.vec3()));
      s.objectFromModel[3] = glm::dvec4(-shift, 1.0);  // the model: the vertices as written
      if (s.mesh.positions.size() < 3) vertices->fail("a mesh needs at least 3 vertices");
      const YamlValue faces = map.require("faces");
      s.mesh.indices = parseFaces(faces, s.mesh.positions.size());
      checkMesh(faces, s.mesh);
    } else {
      map.self().fail("a mesh needs 'file' or 'vertices' and 'faces'");
    }
    known.insert(known.end(), {"file", "scale", "translate", "vertices", "faces", "instances"});
  } else {
    type.fail("unknown shape type '" + t + "' (known: sphere, rectangle, mesh)");
  }
  if (auto e = map.find("emission")) s.emission = parseEmission(YamlMap(*e), ctx);
  if (auto m = map.find("material")) {
    const std::string name = m->string();
    const auto it = ctx.materialIndex.find(name);
    if (it == ctx.materialIndex.end()) m->fail("no material named '" + name + "'");
    s.material = it->second;
    if ((*ctx.materials)[static_cast<size_t>(s.material)].alphaCutout) {
      if (s.kind == ShapeDescription::Kind::kSphere)
        m->fail("material '" + name +
                "' has an alpha cut-out, which needs a mesh with texture "
                "coordinates (a sphere has none)");
      if (s.emission)
        m->fail("material '" + name +
                "' has an alpha cut-out: cut-out emitters are not "
                "supported");
    }
  } else if (meshFile && !s.mesh.materialGroups.empty()) {
    map.finish(known);
    std::vector<ShapeDescription> parts = splitByFileMaterials(
        std::move(s), meshPath, *meshFile, ctx.imported, ctx.materialIndex, ctx.search, scene);
    for (ShapeDescription& part : parts) {
      if (instances)
        parseInstances(*instances, std::move(part), ctx.materialIndex, ctx.origin, out);
      else
        out.push_back(std::move(part));
    }
    return;
  } else if (!s.emission) {
    map.self().fail(
        "shape needs a 'material' (only emitters may omit it: they are then black; an OBJ file "
        "may name its own with usemtl)");
  }
  map.finish(known);
  s.mesh.materialGroups.clear();  // a `material:` overrides the file's
  s.mesh.materialLibraries.clear();
  if (!instances) {
    out.push_back(std::move(s));
    return;
  }
  const size_t first = out.size();
  parseInstances(*instances, std::move(s), ctx.materialIndex, ctx.origin, out);
  // An instance's own material: the same rule on cut-outs as above.
  for (size_t k = first; k < out.size(); ++k)
    if (out[k].emission && out[k].material >= 0 &&
        (*ctx.materials)[static_cast<size_t>(out[k].material)].alphaCutout)
      instances->fail("instance '" + out[k].label +
                      "' has a material with an alpha cut-out, and the shape emits: cut-out "
                      "emitters are not supported");
}

}  // namespace

SceneDescription loadSceneFromText(const std::string& text, const std::string& displayName,
                                   const std::filesystem::path& baseDir,
                                   const LoadOptions& options) {
  const YamlValue root = parseYaml(text, displayName);
  if (root.isNull()) throw InputError({displayName, 1, 1}, "", "the scene file is empty");
  YamlMap top(root);
  Context ctx;
  ctx.baseDir = baseDir;
  ctx.search.directories.push_back(baseDir);
  if (auto paths = top.find("spectra_path")) {
    for (const YamlValue& p : paths->items()) {
      std::filesystem::path dir(p.string());
      if (dir.is_relative()) dir = baseDir / dir;
      if (!isDirectory(dir)) p.fail("directory '" + dir.string() + "' does not exist");
      ctx.search.directories.push_back(dir);
    }
  }
  for (const auto& dir : options.spectraPath) ctx.search.directories.push_back(dir);
  ctx.search.directories.push_back(lutsDirectory() / "spectra");

  SceneDescription scene;
  scene.sourceFile = displayName;
  scene.sourceFnv1a = fnv1aHex(text);
  ctx.search.filesRead = &scene.inputFiles;
  if (auto v = top.find("format")) {
    if (v->string() != "camsim-scene/1")
      v->fail("unsupported format '" + v->string() + "' (this camsim reads camsim-scene/1)");
  }
  scene.name = std::filesystem::path(displayName).stem().string();
  // The name is the stem of every file a render writes (NAME.exr, its temporary
  // .NAME.exr.camsim-tmp-XXXXXX, NAME_ev+0.5_raw.exr): one printable file name, at most
  // kMaxNameBytes so that those stay within the 255 bytes a file name may have.
  const std::optional<YamlValue> nameValue = top.find("name");
  if (nameValue) scene.name = nameValue->string();
  const YamlValue& nameAt = nameValue ? *nameValue : top.self();
  if (scene.name.empty() || scene.name.find_first_of("/\\") != std::string::npos ||
      scene.name == "." || scene.name == "..")
    nameAt.fail("name must be a non-empty file name: not '.' or '..', without '/' or '\\'");
  if (std::any_of(scene.name.begin(), scene.name.end(),
                  [](char c) { return static_cast<unsigned char>(c) < 0x20 || c == 0x7f; }))
    nameAt.fail("name must not hold control characters (it names the output files)");
  if (scene.name.size() > SceneLimits::kMaxNameBytes)
    nameAt.fail("name is " + std::to_string(scene.name.size()) + " bytes long; at most " +
                std::to_string(SceneLimits::kMaxNameBytes) +
                " (it names the output files; limit SceneLimits::kMaxNameBytes)");
  if (auto v = top.find("render")) scene.render = parseRender(YamlMap(*v));
  std::vector<GltfInclude> includes;
  if (auto inc = top.find("include")) includes = parseGltfIncludes(*inc, baseDir, ctx.search);
  const YamlValue cameraValue = top.require("camera");
  scene.camera = parseCamera(YamlMap(cameraValue), ctx.search);
  std::optional<double> gltfYfov;
  if (auto g = YamlMap(cameraValue).find("gltf"))
    gltfYfov = applyGltfCamera(*g, includes, scene.camera, scene.notes);
  // A sensor override replaces these with the sensor's pixel geometry: it refuses them, as
  // the loader refuses them beside a scene's sensor (setSensor, overrides.cpp).
  for (const char* key : kSensorGeometryKeys)
    if (auto v = YamlMap(cameraValue).find(key))
      scene.keyPlaces[std::string("camera.") + key] = v->where();
  ctx.origin = glm::dvec3(scene.camera.worldFromCamera[3]);
  scene.renderOrigin = ctx.origin;
  scene.camera.worldFromCamera[3] = glm::dvec4(0.0, 0.0, 0.0, 1.0);
  if (auto sensor = top.find("sensor")) {
    scene.sensor = parseSensorSettings(YamlMap(*sensor), baseDir, cameraValue, scene.camera);
    scene.keyPlaces["sensor"] = sensor->where();
    if (auto model = YamlMap(*sensor).find("model"))
      scene.keyPlaces["sensor.model"] = model->where();
    for (const auto& f : scene.sensor->spec.sourceFiles) ctx.search.noteRead(f);
  }
  if (gltfYfov) {  // on the sensor's height, now that the sensor has set it
    scene.camera.focalLength = 0.5 * scene.camera.sensorSize.y / std::tan(0.5 * *gltfYfov);
    // focal_length_mm's bound (found by probing: a yfov of 1e-20 rad rendered every sample
    // NaN, a black image, exit 0).
    if (!(scene.camera.focalLength <= 1e2))
      YamlMap(cameraValue)
          .find("gltf")
          ->fail("the glTF camera's yfov, " + formatShortest(*gltfYfov) +
                 " rad, gives a focal length of " +
                 formatNumber(scene.camera.focalLength * 1e3, 4) + " mm on the sensor's " +
                 formatShortest(scene.camera.sensorSize.y * 1e3) +
                 " mm height, beyond focal_length_mm's 1e5");
    if (scene.camera.focusDistance > 0.0 &&
        !(scene.camera.focusDistance > scene.camera.focalLength * 1.0001))
      YamlMap(cameraValue)
          .find("focus_distance_m")
          ->fail("focus distance must exceed 1.0001 × the glTF camera's focal length");
  }
  if (auto isp = top.find("isp")) {
    if (!scene.sensor) isp->fail("isp settings need a sensor");
    scene.isp = parseIspSettings(YamlMap(*isp), scene.sensor->spec, scene.camera.resolution,
                                 scene.keyPlaces);
  }
  if (auto mats = top.find("materials")) {
    YamlMap mmap(*mats);
    for (const std::string& name : mmap.keys()) {
      ctx.materialIndex[name] = static_cast<int>(scene.materials.size());
      scene.materials.push_back(
          parseMaterial(name, YamlMap(*mmap.find(name)), ctx.search, ctx.baseDir));
    }
  }
  std::vector<YamlValue> items;
  if (auto shapes = top.find("shapes"))
    items = shapes->items();
  else if (includes.empty())
    top.require("shapes");
  ctx.materials = &scene.materials;
  for (size_t i = 0; i < items.size(); ++i)
    parseShape(YamlMap(items[i]), i, ctx, scene, scene.shapes);
  addGltfIncludes(includes, scene);
  const YamlValue shapesKey = top.find("shapes") ? *top.find("shapes") : *top.find("include");
  if (scene.shapes.empty()) shapesKey.fail("the scene has no shapes");
  checkClassNumbers(scene, shapesKey);
  if (auto l = top.find("lights")) {
    // The scene's own lights first, then the included assets' (added with their shapes).
    std::vector<LightDescription> own = parseLights(*l, ctx.search, baseDir, scene.renderOrigin);
    scene.lights.insert(scene.lights.begin(), own.begin(), own.end());
  }
  if (auto f = top.find("frames")) {
    scene.frames = parseFrames(YamlMap(*f));
    // Each frame's shutter where the frame starts: the first and last are the furthest from
    // 0, where a short exposure's times are the first to run together.
    try {
      (void)scene.frameCamera(0);
      (void)scene.frameCamera(scene.frames->count - 1);
    } catch (const InputError& e) {
      f->fail(e.message());
    }
    if (const std::string problem = frameTimingProblem(scene); !problem.empty()) f->fail(problem);
  }
  if (auto e = top.find("exports")) parseExports(*e, scene);
  // An aov that needs what the scene lacks: an error at render.aovs.
  const std::vector<Aov>& aovs = scene.render.aovs;
  const auto require = [&](Aov a, bool met, const char* what) {
    if (!met && std::find(aovs.begin(), aovs.end(), a) != aovs.end())
      YamlMap(*top.find("render"))
          .find("aovs")
          ->fail(std::string("aov '") + aovName(a) + "' needs " + what);
  };
  require(Aov::kMotion, scene.frames.has_value(),
          "a frames block: its vectors point to the previous and the next frame");
  require(Aov::kAmodal, hasLabelledShape(scene),
          "a labelled shape: its masks are of the shapes that have a `class:`, and none has");
  require(Aov::kOcclusion, scene.frames.has_value(),
          "a frames block: it tells what the previous and the next frame see");
  top.finish({"format", "name", "spectra_path", "render", "camera", "sensor", "isp", "materials",
              "shapes", "lights", "frames", "include", "exports"});
  // Each file once (as first read), however it was named: keyed by its canonical path
  // (symbolic links and ./.. resolved), one lookup per read.
  std::vector<std::filesystem::path> once;
  std::set<std::filesystem::path> seen;
  for (const auto& f : scene.inputFiles) {
    std::error_code ec;
    std::filesystem::path canonical = std::filesystem::weakly_canonical(f, ec);
    if (ec) canonical = f;
    if (seen.insert(canonical).second) once.push_back(f);
  }
  scene.inputFiles = std::move(once);
  return scene;
}

std::string readSceneFile(const std::filesystem::path& file) {
  std::string ext = file.extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (ext == ".gltf" || ext == ".glb")
    throw InputError({file.string(), 0, 0}, "",
                     "a glTF file is an asset, not a camsim scene: place it in a scene file with "
                     "`include: [{gltf: " +
                         file.filename().string() +
                         "}]` beside a camera (docs/scene-format.md, \"include\")");
  return readInputFile(file, "scene file");
}

std::filesystem::path sceneBaseDir(const std::filesystem::path& file) {
  return file.parent_path().empty() ? std::filesystem::path(".") : file.parent_path();
}

SceneDescription loadScene(const std::filesystem::path& file, const LoadOptions& options) {
  return loadSceneFromText(readSceneFile(file), file.string(), sceneBaseDir(file), options);
}

std::string pinholeExportProblem(const SceneDescription& scene, const Projection& projection) {
  // Both describe the camera by a pinhole matrix (BOP's 3×3 K, KITTI's 3×4 P2).
  for (const ExportFormat f : scene.exports)
    if (!isUndistortedOpenCv(projection) || scene.camera.lens)
      return std::string("export '") + exportFormatName(f) +
             "' needs the camera projection 'opencv' without distortion and no traced lens: its "
             "files describe the camera by a pinhole matrix alone";
  return "";
}

std::string frameTimingProblem(const SceneDescription& scene) {
  if (!scene.frames) return "";
  const double period = 1.0 / scene.frames->rateHz;
  const Shutter shutter = scene.frameShutter();  // before the shift: no rounding by start time
  const double exposure = shutter.close() - shutter.open();
  const int rows = scene.camera.resolution.y;
  const double readout = shutter.rowTime() * rows;
  // A relative 1e-12: a 360° shutter angle's box is the period itself, up to rounding.
  const double limit = period * (1.0 + 1e-12);
  const std::string periodText =
      "the frame period 1/frames.rate_hz = " + formatShortest(period) + " s";
  if (exposure > limit)
    return "each frame's exposure, " + formatShortest(exposure) + " s (camera.shutter), is " +
           "longer than " + periodText +
           ": consecutive frames would expose at the same time; shorten the shutter, set "
           "frames.shutter_angle_deg (at most 360) or lower frames.rate_hz";
  // The longest bracket is exposed within the frame too (found by probing: bracket_ev: [0, 4]
  // at 24 fps exposed 0.27 s).
  const double longest = scene.sensor ? scene.sensor->longestBracketFactor() : 1.0;
  if (longest > 1.0 && exposure * longest > limit)
    return "the longest bracket (sensor.bracket_ev, ×" + formatShortest(longest) +
           ") exposes each frame for " + formatShortest(exposure * longest) + " s, longer than " +
           periodText + "; shorten the shutter, lower the brackets or lower frames.rate_hz";
  if (readout > limit)
    return "the rolling shutter reads its " + std::to_string(rows) + " rows in " +
           formatShortest(readout) + " s (camera.shutter.row_time × rows), longer than " +
           periodText +
           ": a camera reads a frame out before the next; shorten row_time or "
           "lower frames.rate_hz";
  return "";
}

}  // namespace camsim
