// The Python module `camsim` (docs/python.md): its docstring, camsim.InputError, and the
// parts of bindings.h. Library code throws camsim::InputError; this front end turns it into
// the Python exception camsim.InputError, a ValueError whose message is the library's text
// ("file:line:column: key 'k': message", a dict scene "<dict>: key 'k': message").
#include <optional>

#include <pybind11/pybind11.h>

#include "python/bindings.h"
#include "sensor/base/input_error.h"
#include "sensor/base/threads.h"

namespace camsim::python {
namespace {

namespace py = pybind11;

constexpr const char* kModuleDoc =
    R"doc(camsim: a camera-sensor physically based spectral path tracer, from Python.

Scenes: camsim.load(path), camsim.default_scene(), camsim.Scene.from_dict(dict) and
Scene.from_yaml(text), the keys of docs/scene-format.md; cheap overrides on a loaded Scene
(set_pose, set_exposure, set_sensor, set_seed, set_spp). Captures: camsim.capture(scene) or
scene.render() return a dict of NumPy arrays that view camsim's own buffers (no copy).

Units (SI unless said):
  lengths m, times s, wavelengths nm; radiance W·m⁻²·sr⁻¹·nm⁻¹
  "xyz"        CIE 1931 XYZ energy per photosite × 683 lm/W: Y in lm·s (absolute)
  "rgb"        linear Rec.709 on the same scale ((1, 1, 1) has Y = 1 lm·s)
  "electrons"  expected (noise-free) photo-electrons per photosite, e⁻
  "raw"        digital numbers (DN, uint16) as the ADC gives them, black level included
  "acescg"     scene-linear ACEScg, exposed so that 0.18 is mid-grey
  "display"    display-encoded RGB through OpenColorIO (sRGB: [0, 1]); "display8" its PNG bytes
  AOVs         depth/distance/position in m, motion vectors in px, ids uint32
Errors in scenes and overrides raise camsim.InputError (a ValueError). docs/python.md has
the whole API, array shapes and lifetimes, threads, the GIL and Ctrl-C.)doc";

py::handle gInputError;  // the type object, owned by the module (module attribute)

}  // namespace

py::handle inputErrorType() {
  return gInputError;
}

namespace {

// An int or anything with __index__ (a NumPy integer), as a C integer parameter took, within
// 64 bits; not a float or a bool. None otherwise.
std::optional<long long> indexValue(const py::object& value) {
  if (PyBool_Check(value.ptr()) || !PyIndex_Check(value.ptr())) return std::nullopt;
  PyObject* index = PyNumber_Index(value.ptr());
  if (!index) {  // its __index__ raised
    PyErr_Clear();
    return std::nullopt;
  }
  try {
    return py::reinterpret_steal<py::int_>(index).cast<long long>();
  } catch (const py::cast_error&) {  // beyond 64 bits
    return std::nullopt;
  }
}

}  // namespace

long long integerArg(const py::object& value, const std::string& where, const std::string& key,
                     long long lo, long long hi) {
  const std::optional<long long> v = indexValue(value);
  if (!v || *v < lo || *v > hi)
    throw InputError({where, 0, 0}, key,
                     "expected an integer in [" + std::to_string(lo) + ", " + std::to_string(hi) +
                         "], got " + std::string(py::repr(value)));
  return *v;
}

std::filesystem::path pathArg(const py::handle& path, const std::string& where,
                              const std::string& key) {
  PyObject* bytes = nullptr;
  if (!PyUnicode_FSConverter(path.ptr(), &bytes)) {
    // TypeError; UnicodeEncodeError (a ValueError) for a str the file system's encoding
    // cannot hold; ValueError for a NUL (found in review: the encoding error said "NUL").
    const bool unencodable = PyErr_ExceptionMatches(PyExc_UnicodeEncodeError);
    const bool nul = !unencodable && PyErr_ExceptionMatches(PyExc_ValueError);
    PyErr_Clear();
    throw InputError({where, 0, 0}, key,
                     unencodable ? "the path is not valid Unicode text (a lone surrogate)"
                     : nul       ? "a path cannot contain a NUL character ('\\x00')"
                                 : "expected a path (str, bytes or os.PathLike), got " +
                                 std::string(py::str(py::type::of(path).attr("__name__"))));
  }
  const auto owned = py::reinterpret_steal<py::bytes>(bytes);
  return std::filesystem::path(std::string(owned));
}

std::string textArg(const py::handle& text, const std::string& where, const std::string& key) {
  Py_ssize_t size = 0;
  const char* utf8 = PyUnicode_AsUTF8AndSize(text.ptr(), &size);
  if (!utf8) {
    PyErr_Clear();
    throw InputError({where, 0, 0}, key,
                     "is not valid Unicode text (a lone surrogate such as '\\udce9')");
  }
  return std::string(utf8, static_cast<std::size_t>(size));
}

py::str osText(const std::string& text) {
  PyObject* s =
      PyUnicode_DecodeUTF8(text.data(), static_cast<Py_ssize_t>(text.size()), "surrogateescape");
  if (!s) throw py::error_already_set();
  return py::reinterpret_steal<py::str>(s);
}

std::string sensorNameOrPath(const py::handle& sensor, const std::string& where,
                             const std::string& key) {
  return pathArg(sensor, where, key).string();  // a name's NUL, too, would cut a file path
}

int threadCountArg(const py::object& threads, const std::string& where) {
  const std::optional<long long> count = indexValue(threads);
  if (!count) throw threadCountError(where, py::repr(threads));
  checkThreadCount(*count, where);
  return static_cast<int>(*count);
}

}  // namespace camsim::python

PYBIND11_MODULE(camsim, m) {
  namespace py = pybind11;
  using namespace camsim::python;
  m.doc() = kModuleDoc;
  m.attr("__version__") = CAMSIM_VERSION;

  // camsim.InputError(ValueError): str(e) is the library's text; e.file, e.line, e.column
  // (0: unknown), e.key (the dotted key path, "" if none) and e.detail (the message alone).
  PyObject* type = PyErr_NewExceptionWithDoc(
      "camsim.InputError",
      "Bad input: a scene, an override, a sensor or a file. A ValueError whose text names the "
      "file, line and column (a dict scene: \"<dict>\"), and the key path. Attributes: file, "
      "line, column (0 when unknown), key (\"\" when none), detail (the message alone).",
      PyExc_ValueError, nullptr);
  if (type == nullptr) throw py::error_already_set();
  m.add_object("InputError", py::reinterpret_steal<py::object>(type));
  gInputError = m.attr("InputError");
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const camsim::InputError& e) {
      // Text that is not UTF-8 (a path's bytes) as os.fsdecode shows it, not a second error.
      py::object error = inputErrorType()(osText(e.what()));
      error.attr("file") = osText(e.where().file);
      error.attr("line") = e.where().line;
      error.attr("column") = e.where().column;
      error.attr("key") = osText(e.key());
      error.attr("detail") = osText(e.message());
      PyErr_SetObject(inputErrorType().ptr(), error.ptr());
    }
  });

  bindSceneFunctions(m);
  bindCaptureFunctions(m);
  bindFileFunctions(m);
  bindSensorFunctions(m);
}
