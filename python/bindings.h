// The Python module's parts (module.cpp assembles them): each binds one area of camsim.
// Only python/ includes pybind11; these functions call the libraries and hold no state
// between calls (a Scene owns its own description; a capture's arrays own their result).
#pragma once

#include <filesystem>
#include <initializer_list>
#include <memory>
#include <string>
#include <utility>

#include <pybind11/pybind11.h>

#include "integrator/capture/scene_cache.h"
#include "integrator/scene/overrides.h"
#include "integrator/scene/scene_description.h"

namespace camsim::python {

// A loaded scene: the description the loader produced, with the overrides applied since.
// What a render reads; capture() renders a copy, so one Scene can be captured again and again.
// `built` keeps the renderable Scene (BVH, materials, lights) of its last capture, which the
// next capture reuses when Scene::canRetarget allows (scene_cache.h). It is the Scene's
// own, never shared: copy() starts without one. Every override here changes only what a
// built Scene can be retargeted to (camera, spp, seed, sensor); one that changed shapes,
// materials, lights, textures or the render origin would have to reset `built`.
struct PyScene {
  explicit PyScene(SceneDescription d) : description(std::move(d)) {}
  SceneDescription description;
  // Null while a capture has it (taken with the GIL held, given back after): two captures of
  // one Scene at once never share it; the second builds its own.
  std::unique_ptr<SceneCache> built = std::make_unique<SceneCache>();
};

// Scene, load(), default_scene(), Scene.from_dict/from_yaml and the overrides.
void bindSceneFunctions(pybind11::module_& m);
// capture() and Scene.render(): a capture's arrays and its metadata.
void bindCaptureFunctions(pybind11::module_& m);
// read_exr() and read_png(): the project's own readers, for comparing with the CLI's files.
void bindFileFunctions(pybind11::module_& m);
// expose(), develop(), display() (issue 23 item 4).
void bindSensorFunctions(pybind11::module_& m);

// The Python exception camsim.InputError (a ValueError), created by module.cpp.
pybind11::handle inputErrorType();

// A `threads=` argument as the library's count (sensor/base/threads.h), InputError at
// `where` for any int out of its range: bound as a C int, one past 32 bits was pybind11's
// TypeError ("incompatible function arguments") instead (found by probing: 2**40).
int threadCountArg(const pybind11::object& threads, const std::string& where);

// An integer argument (an int or anything with __index__, not a float or a bool) in [lo, hi]:
// camsim.InputError at `where`, naming `key`, otherwise (pybind11's own conversion raised
// TypeError for a negative seed).
long long integerArg(const pybind11::object& value, const std::string& where,
                     const std::string& key, long long lo, long long hi);

// A path argument as open() takes it (str, bytes or os.PathLike), as the OS's bytes
// (os.fsencode: a name that is not UTF-8 still opens); InputError at `where` naming `key` for
// another type or a NUL character (found by probing: the path was cut there, so another
// file was read, and bytes were taken as their repr "b'...'").
std::filesystem::path pathArg(const pybind11::handle& path, const std::string& where,
                              const std::string& key);
// A str as UTF-8; InputError at `where` naming `key` for one that is not valid Unicode (a
// lone surrogate such as "\udce9": pybind11's cast raised RuntimeError).
std::string textArg(const pybind11::handle& text, const std::string& where, const std::string& key);

// Text from the OS (a path's bytes, maybe not UTF-8) as os.fsdecode shows it.
pybind11::str osText(const std::string& text);

// A sensor argument: a preset name or a file, as a str or os.PathLike (pathArg).
std::string sensorNameOrPath(const pybind11::handle& sensor, const std::string& where,
                             const std::string& key);

// Overrides of a loaded scene (scene_overrides.cpp), through the library's override table
// (integrator/scene/overrides.h). Each throws InputError naming the scene key ("<override>"
// as its file) for a bad value; none reads a file but a sensor override's sensor
// description, and none touches shapes, materials, textures or lights.
// The camera's pose in the scene file's world coordinates (world_from_camera: columns
// right, up, forward, position, as the scene format's key); checked by the scene loader.
void overridePoseLookAt(SceneDescription& d, const glm::dvec3& position, const glm::dvec3& lookAt,
                        const glm::dvec3& up);
void overridePoseMatrix(SceneDescription& d, const glm::dmat4& worldFromCamera);
// One Python value into o as setting s (a wrong type: InputError naming typeKey).
void setOverrideFromPython(Overrides& o, const OverrideSetting& s, const pybind11::handle& value,
                           const std::string& typeKey);
// A dict key → value of overrides.h's keys (None: not set) into Overrides; an unknown key or
// a wrong type: InputError naming prefix + key.
Overrides overridesFromDict(const pybind11::dict& overrides, const std::string& prefix);
// Key → value pairs of overrides.h's keys (None: not set), applied together; a wrong type
// or a bad value: InputError naming the scene key (the set_* methods).
void applyPythonOverrides(SceneDescription& d,
                          std::initializer_list<std::pair<const char*, pybind11::object>> values);
// The overrides dict of load() (the CLI's render flags): every key of overrides.h's table
// (sensor, spp, seed, exposure_time_s, f_number, iso, noise, noise_seed, pose).
void applyOverrides(SceneDescription& d, const pybind11::dict& overrides);

}  // namespace camsim::python
