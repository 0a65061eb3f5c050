// camsim.Scene and the ways to make one: load(path), default_scene(), Scene.from_dict(d),
// Scene.from_yaml(text). Every way goes through the scene loader (integrator/scene), so the
// keys, defaults and errors are the YAML format's (docs/scene-format.md): a dict is written
// as JSON text (YAML reads JSON) and loaded as "<dict>", its errors naming the key path.
#include <charconv>
#include <cmath>
#include <filesystem>
#include <string>

#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include "integrator/capture/default_scene.h"
#include "integrator/scene/scene_loader.h"
#include "python/bindings.h"
#include "sensor/base/input_error.h"
#include "sensor/io/json_writer.h"

namespace camsim::python {
namespace {

namespace py = pybind11;

constexpr const char* kDictName = "<dict>";

std::string shortestNumber(double v) {
  if (std::isnan(v)) return ".nan";
  if (std::isinf(v)) return v > 0 ? ".inf" : "-.inf";
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, v);
  return std::string(buffer, result.ptr);
}

[[noreturn]] void dictFail(const std::string& key, const std::string& message) {
  throw InputError(SourceLocation{kDictName, 0, 0}, key, message);
}

std::string typeName(const py::handle& v) {
  return py::str(py::type::of(v).attr("__name__"));
}

// v as JSON (YAML's .nan and .inf for non-finite floats, so that the loader reports them as
// it does in a file); `key`: v's key path, for the error of a value JSON cannot hold.
// Below yaml-cpp's depth guard (500, counting the top level and scalars): a dict or list
// that contains itself recursed here until the stack overflowed (found by probing: a
// segfault), and deeper ones get their key path here, not yaml-cpp's bare message.
constexpr int kMaxDictDepth = 400;

void emitValue(const py::handle& v, const std::string& key, std::string& out, int depth = 0) {
  if (depth > kMaxDictDepth)
    dictFail(key.size() > 120 ? key.substr(0, 120) + "…" : key,
             "nested more than " + std::to_string(kMaxDictDepth) +
                 " levels deep (does a dict or list contain itself?)");
  if (v.is_none()) {
    out += "null";
  } else if (py::isinstance<py::bool_>(v)) {
    out += v.cast<bool>() ? "true" : "false";
  } else if (py::isinstance<py::int_>(v)) {
    out += std::string(py::str(v));
  } else if (py::isinstance<py::float_>(v)) {
    out += shortestNumber(v.cast<double>());
  } else if (py::isinstance<py::str>(v)) {
    out += JsonObject::quoted(textArg(v, kDictName, key));
  } else if (py::hasattr(v, "__fspath__")) {
    out +=
        JsonObject::quoted(textArg(py::module_::import("os").attr("fsdecode")(v), kDictName, key));
  } else if (py::isinstance<py::dict>(v)) {
    out += "{";
    bool first = true;
    for (const auto& [k, item] : py::reinterpret_borrow<py::dict>(v)) {
      if (!py::isinstance<py::str>(k))
        dictFail(key, "keys must be str, got " + typeName(k) + " " + std::string(py::repr(k)));
      const std::string name = textArg(k, kDictName, key);
      out += (first ? "" : ", ") + JsonObject::quoted(name) + ": ";
      emitValue(item, key.empty() ? name : key + "." + name, out, depth + 1);
      first = false;
    }
    out += "}";
  } else if (py::hasattr(v, "tolist") && !py::isinstance<py::str>(v)) {
    emitValue(v.attr("tolist")(), key, out, depth + 1);  // NumPy arrays and scalars
  } else if (py::isinstance<py::list>(v) || py::isinstance<py::tuple>(v)) {
    out += "[";
    std::size_t i = 0;
    for (const py::handle item : v) {
      out += i ? ", " : "";
      emitValue(item, key + "[" + std::to_string(i) + "]", out, depth + 1);
      ++i;
    }
    out += "]";
  } else {
    dictFail(key, "a " + typeName(v) + " is not a scene value (dict, list, str, number, bool)");
  }
}

PyScene withOverrides(SceneDescription d, const std::optional<py::dict>& overrides) {
  if (overrides) applyOverrides(d, *overrides);
  return PyScene{std::move(d)};
}

PyScene loadPath(const py::object& path, const std::optional<py::dict>& overrides) {
  const std::filesystem::path p = pathArg(path, "<load>", "path");
  SceneDescription d;
  {
    py::gil_scoped_release release;  // meshes and textures are read here
    d = loadSceneFromText(readSceneFile(p), p.string(), sceneBaseDir(p));
  }
  return withOverrides(std::move(d), overrides);
}

PyScene loadDefault(const std::optional<py::dict>& overrides) {
  return withOverrides(
      loadSceneFromText(std::string(defaultSceneText()), std::string(kDefaultSceneName), "."),
      overrides);
}

PyScene loadDict(const py::object& scene, const py::object& baseDir,
                 const std::optional<py::dict>& overrides) {
  // Taken as any object (a py::dict parameter made pybind11 raise its TypeError for a
  // list): the top level that is not a mapping is bad input like any other.
  if (!py::isinstance<py::dict>(scene))
    dictFail("",
             "the scene's top level must be a dict of the scene's keys (camera, shapes, …), "
             "got a " +
                 typeName(scene));
  std::string text;
  emitValue(scene, "", text);
  const std::filesystem::path base = pathArg(baseDir, "<scene>", "base_dir");
  SceneDescription d;
  try {
    py::gil_scoped_release release;
    d = loadSceneFromText(text + "\n", kDictName, base);
  } catch (const InputError& e) {
    // The JSON text's line and column mean nothing to the caller: the key path does.
    if (e.where().file != kDictName) throw;
    dictFail(e.key(), e.message());
  }
  return withOverrides(std::move(d), overrides);
}

PyScene loadText(const std::string& text, const std::string& name, const py::object& baseDir,
                 const std::optional<py::dict>& overrides) {
  const std::filesystem::path base = pathArg(baseDir, "<scene>", "base_dir");
  SceneDescription d;
  {
    py::gil_scoped_release release;
    d = loadSceneFromText(text, name, base);
  }
  return withOverrides(std::move(d), overrides);
}

// World-from-camera in the scene file's world (the render origin added back), row by row.
py::array_t<double> worldFromCamera(const SceneDescription& d) {
  py::array_t<double> out({4, 4});
  auto a = out.mutable_unchecked<2>();
  glm::dmat4 m = d.camera.worldFromCamera;
  m[3] = glm::dvec4(glm::dvec3(m[3]) + d.renderOrigin, 1.0);
  for (py::ssize_t r = 0; r < 4; ++r)
    for (py::ssize_t c = 0; c < 4; ++c) a(r, c) = m[static_cast<int>(c)][static_cast<int>(r)];
  return out;
}

glm::dvec3 toVec3(const std::vector<double>& v, const char* key) {
  if (v.size() != 3)
    throw InputError(SourceLocation{"<override>", 0, 0}, key, "expected a list of 3 numbers");
  return {v[0], v[1], v[2]};
}

}  // namespace

void bindSceneFunctions(py::module_& m) {
  auto scene = py::class_<PyScene>(m, "Scene", R"doc(
A loaded scene: what the scene loader read (docs/scene-format.md), with the overrides set
since. Units are SI throughout (m, s, W, nm for wavelengths); the camera pose is in the scene
file's world coordinates.

Make one with camsim.load(path), camsim.default_scene(), Scene.from_dict(d) or
Scene.from_yaml(text). The set_* overrides change it in place and return it (chainable);
they touch no geometry, so no mesh, texture or environment map is read again: the meshes,
decoded textures and spectra stay in memory in the Scene. The Scene also keeps what its
last capture built (Embree BVH, materials, lights) and the next capture renders on it when
only the camera pose, exposure, f-number, ISO, sensor, seeds or spp changed — the same
bytes as a fresh build; it is rebuilt when something with keyframed motion would need
another exposure window (docs/python.md, "Cheap overrides"). meta["scene_reused"] says which
happened; capture(reuse=False) builds afresh. Two Scenes never share state: copy() gives an
independent Scene (without the built one).
)doc");

  const auto overridesDoc = R"doc(
overrides: an optional dict of the CLI's render flags, applied after loading, in this order:
  sensor (preset name or sensor file), spp (int), seed (int), target_error (an estimated
  MRAE: render in passes until it is reached), time_limit_s (s: passes stop before it),
  exposure_time_s (s: the scene's shutter stretched to this effective time, as
  --exposure-time-s), f_number,
  iso (scenes with a sensor), noise ("none" | "photon" | "full"), noise_seed (int),
  pose (as set_pose: {position, look_at, up} or a 4×4 world_from_camera), projection (the
  camera model: camera.projection's map as a dict or YAML/JSON text, as set_projection).
Raises camsim.InputError (a ValueError) for a bad scene or override, naming the file, line
and column (a dict: the key path) and the key.)doc";

  scene.def_static("load", &loadPath, py::arg("path"), py::kw_only(),
                   py::arg("overrides") = py::none(),
                   (std::string("Loads a scene file (YAML or JSON; relative paths in it resolve "
                                "against its directory).\n") +
                    overridesDoc)
                       .c_str());
  scene.def_static("default", &loadDefault, py::kw_only(), py::arg("overrides") = py::none(),
                   (std::string("The built-in Cornell box (scenes/cornell_box.yaml), as "
                                "`camsim render` without a scene.\n") +
                    overridesDoc)
                       .c_str());
  scene.def_static("from_dict", &loadDict, py::arg("scene"), py::kw_only(),
                   py::arg("base_dir") = ".", py::arg("overrides") = py::none(),
                   (std::string(R"doc(A scene from a dict with the keys of the YAML format, e.g.
  {"camera": {"position": [0, 0, -1], "look_at": [0, 0, 0]},
   "materials": {"m": {"type": "diffuse"}},
   "shapes": [{"type": "sphere", "centre": [0, 0, 0], "radius": 1, "material": "m"}]}
Values may be dicts, lists, tuples, NumPy arrays and scalars, str, int, float, bool and
paths. It is written as JSON and read by the very same loader as a file, so the keys and
errors are identical; an error names "<dict>" and the key path, e.g.
  <dict>: key 'shapes[0].radius': value -1 is out of range ...
base_dir: the directory relative file names (meshes, textures, spectra) resolve against.
)doc") + overridesDoc)
                       .c_str());
  scene.def_static("from_yaml", &loadText, py::arg("text"), py::kw_only(),
                   py::arg("name") = "<text>", py::arg("base_dir") = ".",
                   py::arg("overrides") = py::none(),
                   (std::string("A scene from YAML (or JSON) text; `name` names it in errors "
                                "(name:line:column), relative paths resolve against base_dir.\n") +
                    overridesDoc)
                       .c_str());

  m.def(
      "override_settings",
      [] {
        py::list out;
        for (const OverrideSetting& s : overrideSettings()) {
          py::dict d;
          d["key"] = std::string(s.key);
          d["scene_key"] = std::string(s.sceneKey);
          d["unit"] = std::string(s.unit);
          d["flag"] = overrideFlag(s);
          d["help"] = std::string(s.help);
          d["range"] = overrideRangeText(s);
          const bool integer = s.type == OverrideType::kInteger;
          const bool number = s.type == OverrideType::kNumber;
          d["type"] = integer                               ? "int"
                      : number                              ? "float"
                      : s.type == OverrideType::kPose       ? "pose"
                      : s.type == OverrideType::kProjection ? "projection"
                                                            : "str";
          if (integer) {
            d["lo"] = s.integers.lo;
            d["hi"] = s.integers.hi;
            d["lo_open"] = false;
          } else if (number) {
            d["lo"] = s.numbers.lo;
            d["hi"] = s.numbers.hi;
            d["lo_open"] = s.numbers.loOpen;
          }
          out.append(d);
        }
        return out;
      },
      R"doc(The overrides a front end can set (integrator/scene/overrides.h), one dict each in the
order they apply: key (the keyword of capture()/render() and of the overrides dict), scene_key,
unit, flag (camsim render's), help, range (as errors print it), type ("int", "float", "str",
"pose", "projection": a dict or YAML/JSON text) and, for numbers, lo, hi and lo_open (the range (lo, hi] rather than [lo, hi]).)doc");
  scene.def(
      "copy", [](const PyScene& s) { return PyScene{s.description}; },
      "An independent copy (meshes and decoded textures are copied in memory; the built "
      "renderable scene is not shared: the copy's first capture builds its own).");
  scene.def(
      "set_pose",
      [](PyScene& s, std::optional<std::vector<double>> position,
         std::optional<std::vector<double>> lookAt, std::vector<double> up,
         std::optional<py::array_t<double, py::array::c_style | py::array::forcecast>> matrix)
          -> PyScene& {
        if (matrix) {
          if (position || lookAt)
            throw InputError(SourceLocation{"<override>", 0, 0}, "camera.world_from_camera",
                             "give world_from_camera or position and look_at, not both");
          if (matrix->ndim() != 2 || matrix->shape(0) != 4 || matrix->shape(1) != 4)
            throw InputError(SourceLocation{"<override>", 0, 0}, "camera.world_from_camera",
                             "expected a 4×4 matrix");
          auto a = matrix->unchecked<2>();
          glm::dmat4 w(1.0);
          for (py::ssize_t r = 0; r < 4; ++r)
            for (py::ssize_t c = 0; c < 4; ++c)
              w[static_cast<int>(c)][static_cast<int>(r)] = a(r, c);
          overridePoseMatrix(s.description, w);
        } else {
          if (!position || !lookAt)
            throw InputError(SourceLocation{"<override>", 0, 0}, "camera",
                             "give position and look_at, or world_from_camera");
          overridePoseLookAt(s.description, toVec3(*position, "camera.position"),
                             toVec3(*lookAt, "camera.look_at"), toVec3(up, "camera.up"));
        }
        return s;
      },
      py::kw_only(), py::arg("position") = py::none(), py::arg("look_at") = py::none(),
      py::arg("up") = std::vector<double>{0.0, 1.0, 0.0}, py::arg("world_from_camera") = py::none(),
      py::return_value_policy::reference_internal,
      R"doc(The camera's rest pose, in the scene file's world coordinates (m): position and look_at
(and up, default +y), or world_from_camera, a 4×4 matrix whose columns are right, up,
forward, position with right = forward × up (determinant −1), as the scene format's
camera.world_from_camera. Checked by the scene loader (same messages). Camera motion
keyframes, lens and sensor are kept. Shapes and lights stay in the render space of the
loaded scene (its origin: the first camera position), so a render equals a reload of the
scene at this pose to float rounding, not always bit for bit. Returns the Scene.)doc");
  scene.def(
      "set_projection",
      [](PyScene& s, const py::object& projection) -> PyScene& {
        applyPythonOverrides(s.description, {{"projection", projection}});
        return s;
      },
      py::arg("projection"), py::return_value_policy::reference_internal,
      R"doc(The camera model, as the scene's camera.projection (docs/camera.md): a dict such as
{"model": "kannala_brandt", "k1": 0.02, "k2": -0.003} or {"model": "equidistant",
"max_field_angle_deg": 95}, or the same as YAML/JSON text. Keys: model (opencv,
kannala_brandt, equidistant, equisolid, stereographic, orthographic, ftheta, unified,
double_sphere, equirectangular), k1…k6, p1, p2, s1…s4, tau_x, tau_y, xi, alpha,
max_field_angle_deg, and fx, fy, cx, cy (px; all four or none: then they follow the lens).
It replaces the scene's projection (or distortion) whole. Checked by the scene loader (same
messages, key camera.projection.<key>); a model other than opencv is refused when the scene's
camera.aperture.pupil is flat. Returns the Scene.)doc");
  scene.def(
      "set_exposure",
      [](PyScene& s, const py::object& t, const py::object& n, const py::object& iso) -> PyScene& {
        applyPythonOverrides(s.description,
                             {{"exposure_time_s", t}, {"f_number", n}, {"iso", iso}});
        return s;
      },
      py::kw_only(), py::arg("exposure_time_s") = py::none(), py::arg("f_number") = py::none(),
      py::arg("iso") = py::none(), py::return_value_policy::reference_internal,
      R"doc(Exposure: exposure_time_s (s, the effective time: the scene's shutter curve stretched to
it, as camsim render --exposure-time), f_number (the entrance pupil follows: D = f/N),
iso (scenes with a sensor). Returns the Scene.)doc");
  scene.def(
      "set_sensor",
      [](PyScene& s, const py::object& model, const py::object& iso) -> PyScene& {
        applyPythonOverrides(s.description, {{"sensor", model}, {"iso", iso}});
        return s;
      },
      py::arg("model"), py::kw_only(), py::arg("iso") = py::none(),
      py::return_value_policy::reference_internal,
      R"doc(The sensor, as the scene's sensor.model: a preset of luts/sensors/ (smartphone-1.4um,
fullframe-d850, ideal-xyz) or a sensor file. ISO becomes its base ISO unless iso is given;
the camera's sensor size and fill factor follow its pixel pitch; a sensor already there
keeps its noise mode, seeds, auto-exposure and brackets. Reads only the sensor
description. Returns the Scene.)doc");
  scene.def(
      "set_seed",
      [](PyScene& s, const py::object& seed, const py::object& noiseSeed) -> PyScene& {
        applyPythonOverrides(s.description, {{"seed", seed}, {"noise_seed", noiseSeed}});
        return s;
      },
      py::arg("seed") = py::none(), py::kw_only(), py::arg("noise_seed") = py::none(),
      py::return_value_policy::reference_internal,
      "The render seed (render.seed) and the sensor's temporal-noise seed (sensor.noise_seed). "
      "Returns the Scene.");
  scene.def(
      "set_spp",
      [](PyScene& s, const py::object& spp) -> PyScene& {
        applyPythonOverrides(s.description, {{"spp", spp}});
        return s;
      },
      py::arg("spp"), py::return_value_policy::reference_internal,
      "Samples per pixel (render.spp). Returns the Scene.");
  scene.def(
      "set_guiding",
      [](PyScene& s, const py::object& guiding) -> PyScene& {
        applyPythonOverrides(s.description, {{"guiding", guiding}});
        return s;
      },
      py::arg("guiding"), py::return_value_policy::reference_internal,
      "Path guiding (render.guiding): 1 on, 0 off. Returns the Scene.");
  scene.def(
      "set_passes",
      [](PyScene& s, const py::object& targetError, const py::object& timeLimitS) -> PyScene& {
        applyPythonOverrides(s.description,
                             {{"target_error", targetError}, {"time_limit_s", timeLimitS}});
        return s;
      },
      py::kw_only(), py::arg("target_error") = py::none(), py::arg("time_limit_s") = py::none(),
      py::return_value_policy::reference_internal,
      "Render in passes (render.target_error: the estimated MRAE to stop at; "
      "render.time_limit_s: seconds of render time not to pass); spp is then the first pass. "
      "Returns the Scene.");
  scene.def(
      "set_adaptive",
      [](PyScene& s, const py::object& threshold) -> PyScene& {
        applyPythonOverrides(s.description, {{"adaptive_threshold", threshold}});
        return s;
      },
      py::arg("threshold"), py::return_value_policy::reference_internal,
      "Adaptive sampling (render.adaptive_threshold): a pixel stops taking samples once its "
      "estimated relative error is below threshold (at the image's mean brightness); spp is "
      "then the most a pixel gets. Returns the Scene.");

  scene.def_property_readonly(
      "name", [](const PyScene& s) { return osText(s.description.name); },
      "The output base name (the scene's name, else its file's stem).");
  scene.def_property_readonly(
      "source_file", [](const PyScene& s) { return osText(s.description.sourceFile); },
      "What it was loaded from (a path, \"<dict>\", or the default scene's name).");
  scene.def_property_readonly(
      "input_files",
      [](const PyScene& s) {
        py::list out;  // as os.fsdecode shows a name that is not UTF-8
        for (const auto& f : s.description.inputFiles) out.append(osText(f.string()));
        return out;
      },
      "Every other file the loader read (meshes, textures, spectra, the sensor description).");
  scene.def_property_readonly(
      "notes", [](const PyScene& s) { return s.description.notes; },
      "What the loader left out or changed (features of imported glTF, OBJ/.mtl assets that "
      "camsim ignores or approximates), one sentence each; the CLI prints them.");
  scene.def_property_readonly(
      "resolution",
      [](const PyScene& s) {
        return py::make_tuple(s.description.camera.resolution.x, s.description.camera.resolution.y);
      },
      "(width, height) in pixels.");
  scene.def_property_readonly(
      "spp", [](const PyScene& s) { return s.description.render.spp; }, "Samples per pixel.");
  scene.def_property_readonly(
      "seed", [](const PyScene& s) { return s.description.render.seed; }, "The render seed.");
  scene.def_property_readonly(
      "exposure_time_s",
      [](const PyScene& s) { return s.description.camera.shutter.effectiveTime(); },
      "The effective exposure time of the shutter (s).");
  scene.def_property_readonly(
      "f_number", [](const PyScene& s) { return s.description.camera.fNumber; },
      "The lens f-number N.");
  scene.def_property_readonly(
      "sensor",
      [](const PyScene& s) -> py::object {
        if (!s.description.sensor) return py::none();
        return py::str(s.description.sensor->spec.name);
      },
      "The sensor's name, or None (the film records CIE XYZ only).");
  scene.def_property_readonly(
      "iso",
      [](const PyScene& s) -> py::object {
        return s.description.sensor ? py::object(py::float_(s.description.sensor->iso))
                                    : py::none();
      },
      "The sensor's ISO, or None without a sensor.");
  scene.def_property_readonly(
      "frames",
      [](const PyScene& s) { return s.description.frames ? s.description.frames->count : 1; },
      "Frames per capture: the frames block's count (a sequence), else 1.");
  scene.def_property_readonly(
      "aovs",
      [](const PyScene& s) {
        std::vector<std::string> out;
        for (Aov a : s.description.render.aovs) out.emplace_back(aovName(a));
        return out;
      },
      "The ground-truth layers asked for (render.aovs).");
  scene.def_property_readonly(
      "world_from_camera", [](const PyScene& s) { return worldFromCamera(s.description); },
      "The camera's rest pose as a 4×4 float64 array (columns right, up, forward, position; "
      "world coordinates, m).");
  scene.def("__repr__", [](const PyScene& s) {
    const SceneDescription& d = s.description;
    return "<camsim.Scene '" + d.name + "' " + std::to_string(d.camera.resolution.x) + "x" +
           std::to_string(d.camera.resolution.y) + ", " + std::to_string(d.render.spp) + " spp" +
           (d.sensor ? ", sensor " + d.sensor->spec.name : std::string()) + ">";
  });

  m.attr("load") = scene.attr("load");
  m.attr("default_scene") = scene.attr("default");
}

}  // namespace camsim::python
