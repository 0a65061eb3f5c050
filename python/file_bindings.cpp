// camsim.read_exr() and camsim.read_png(): the project's own readers (sensor/io), so that
// Python can compare a capture's arrays with the files `camsim render` writes, value for
// value (Debian has no Python OpenEXR module). They copy: files are not capture buffers.
#include <pybind11/numpy.h>

#include "python/bindings.h"
#include "sensor/io/exr_io.h"
#include "sensor/io/png_io.h"

namespace camsim::python {
namespace {

namespace py = pybind11;

py::dict readExrFile(const py::object& path) {
  const std::filesystem::path file = pathArg(path, "<read_exr>", "path");
  ExrFile f;
  {
    py::gil_scoped_release release;
    f = readExr(file);
  }
  const Image& img = f.image;
  py::dict channels;
  const std::size_t n = img.channels.size();
  for (std::size_t c = 0; c < n; ++c) {
    py::array_t<float> a({img.height, img.width});
    float* out = a.mutable_data();
    for (std::size_t p = 0;
         p < static_cast<std::size_t>(img.width) * static_cast<std::size_t>(img.height); ++p)
      out[p] = img.pixels[p * n + c];
    channels[py::str(img.channels[c])] = a;
  }
  py::dict metadata;
  for (const auto& [k, v] : f.metadata) metadata[py::str(k)] = v;
  py::dict out;
  out["channels"] = channels;
  out["metadata"] = metadata;
  return out;
}

py::array readPngFile(const py::object& path) {
  const std::filesystem::path file = pathArg(path, "<read_png>", "path");
  PngImage png;
  {
    py::gil_scoped_release release;
    png = readPng(file);
  }
  const std::vector<py::ssize_t> shape = {png.height, png.width, png.channels};
  if (png.bitDepth == 16) {
    py::array_t<std::uint16_t> a(shape);
    std::copy(png.samples.begin(), png.samples.end(), a.mutable_data());
    return a;
  }
  py::array_t<std::uint8_t> a(shape);
  std::uint8_t* out = a.mutable_data();
  for (std::size_t i = 0; i < png.samples.size(); ++i)
    out[i] = static_cast<std::uint8_t>(png.samples[i]);
  return a;
}

}  // namespace

void bindFileFunctions(py::module_& m) {
  m.def("read_exr", &readExrFile, py::arg("path"),
        R"doc(Reads an OpenEXR file with camsim's reader: {"channels": {name: float32 (H, W)},
"metadata": {name: str}} (string attributes only). A raw EXR's "raw.DN" holds DN as float
(exact), "electrons.<c>" e⁻; NAME.exr's R, G, B and XYZ.* are in lm·s per photosite.
Raises camsim.InputError if the file cannot be read as an EXR.)doc");
  m.def("read_png", &readPngFile, py::arg("path"),
        R"doc(Reads a PNG with camsim's reader: uint8 (or uint16 for 16-bit files) (H, W, channels);
palettes become RGB(A). Raises camsim.InputError for a file it cannot read.)doc");
}

}  // namespace camsim::python
