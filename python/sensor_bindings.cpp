// The sensor on its own (docs/python.md, "The sensor on its own"): camsim.Sensor, expose(),
// develop() and display(), so that one noise-free render feeds many noise draws, ISOs and
// sensors. They call the same library functions as a capture's steps 5 and 6 and the CLI's
// display output (sensor/model/sensor_model.h exposeChannels, sensor/isp/isp_pipeline.h
// developRaw, sensor/isp/color_management.h OcioProcessor), so for the same inputs they give
// the capture's bytes:
//
// | function  | input                                 | output |
// |-----------|---------------------------------------|--------|
// | expose    | expected e⁻ per photosite, float (h, w); stacked (h, w, C) | raw DN uint16 (h, w) / (h, w, C); frames=n: (n, …) |
// | develop   | raw DN uint16 (h, w); stacked (h, w, C) or a capture's dict | scene-linear ACEScg float32 (h, w, 3) |
// | display   | ACEScg float (h, w, 3)                | display-encoded RGB float32, or uint8/uint16 code values |
//
// Each releases the GIL while it computes; expose() checks for Ctrl-C between groups of
// frames and raises KeyboardInterrupt.
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <pybind11/numpy.h>
#include <pybind11/stl.h>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <limits>
#include <optional>

#include "python/bindings.h"
#include "sensor/base/format.h"
#include "sensor/base/input_error.h"
#include "sensor/base/luts_directory.h"
#include "sensor/base/threads.h"
#include "sensor/io/dark_frame_reader.h"
#include "sensor/io/expose_file.h"
#include "sensor/io/output_set.h"
#include "sensor/isp/color_management.h"
#include "sensor/isp/isp_pipeline.h"
#include "sensor/model/sensor_model.h"
#include "sensor/model/sensor_spec.h"
#include "sensor/spectra/spectral_data.h"

namespace camsim::python {
namespace {

namespace py = pybind11;

[[noreturn]] void fail(const char* function, const std::string& key, const std::string& message) {
  throw InputError(SourceLocation{function, 0, 0}, key, message);
}

// A sensor quantity at an ISO, its error named as the method's (found by probing: "<input>",
// no key).
template <double (SensorSpec::*quantity)(double) const>
auto ofIso(const char* function) {
  return [function](const SensorSpec& s, double iso) {
    try {
      return (s.*quantity)(iso);
    } catch (const InputError& e) {
      fail(function, "iso", e.message());
    }
  };
}

// A float image of one or C channels from a NumPy array (h, w) or (h, w, C), any real dtype;
// every value finite and ≥ 0 (electrons). Copies, with the GIL held.
Image electronsImage(const py::array& input, const SensorSpec& spec) {
  const auto a = py::array_t<float, py::array::c_style | py::array::forcecast>::ensure(input);
  if (!a) fail("<expose>", "electrons", "expected a NumPy array of numbers");
  const int planes = spec.cfa.isStacked() ? static_cast<int>(spec.cfa.channels.size()) : 1;
  const bool ok = planes == 1 ? a.ndim() == 2 : a.ndim() == 3 && a.shape(2) == planes;
  if (!ok || a.shape(0) == 0 || a.shape(1) == 0)
    fail("<expose>", "electrons",
         planes == 1
             ? "expected a 2-D array (height, width) of electrons for sensor '" + spec.name + "'"
             : "expected a 3-D array (height, width, " + std::to_string(planes) +
                   ") of electrons for the stacked sensor '" + spec.name + "'");
  if (a.shape(0) > (1 << 20) || a.shape(1) > (1 << 20))
    fail("<expose>", "electrons", "image larger than 2^20 photosites per side");
  std::vector<std::string> names = planes == 1 ? std::vector<std::string>{"e"} : spec.cfa.channels;
  Image img(static_cast<int>(a.shape(1)), static_cast<int>(a.shape(0)), std::move(names));
  std::memcpy(img.pixels.data(), a.data(), img.pixels.size() * sizeof(float));
  for (std::size_t i = 0; i < img.pixels.size(); ++i) {
    const float v = img.pixels[i];
    if (std::isfinite(v) && v >= 0.0f) continue;
    const std::size_t p = i / static_cast<std::size_t>(planes);
    fail("<expose>", "electrons",
         "value " + std::to_string(v) + " at row " +
             std::to_string(p / static_cast<std::size_t>(img.width)) + ", column " +
             std::to_string(p % static_cast<std::size_t>(img.width)) +
             ": electrons must be finite and ≥ 0");
  }
  return img;
}

NoiseMode noiseMode(const std::string& name) {
  if (auto m = noiseModeFromName(name)) return *m;
  fail("<expose>", "noise", "unknown noise mode '" + name + "' (one of " + noiseModeNames() + ")");
}

// Writes raws (one per plane) into out at frame f: (h, w) per mosaic frame, (h, w, C) per
// stacked frame, as NumPy's row-major layout.
void storeFrame(const std::vector<RawImage>& raws, std::uint16_t* out) {
  if (raws.size() == 1) {
    std::memcpy(out, raws[0].dn.data(), raws[0].dn.size() * sizeof(std::uint16_t));
    return;
  }
  const std::size_t c = raws.size();
  for (std::size_t k = 0; k < c; ++k)
    for (std::size_t p = 0; p < raws[k].dn.size(); ++p) out[p * c + k] = raws[k].dn[p];
}

py::array_t<std::uint16_t> exposeFrames(const py::array& electrons, const SensorSpec& sensor,
                                        const py::object& seedArg, const py::object& framesArg,
                                        const py::object& firstFrameArg, double exposureTimeS,
                                        std::optional<double> iso, double exposureScale,
                                        const std::string& noise, const py::object& threadsArg) {
  const int threads = threadCountArg(threadsArg, "<expose>");
  constexpr long long kMaxIndex = std::numeric_limits<long long>::max();
  const auto seed =
      static_cast<std::uint64_t>(integerArg(seedArg, "<expose>", "seed", 0, kMaxIndex));
  const auto firstFrame = static_cast<std::uint64_t>(
      integerArg(firstFrameArg, "<expose>", "first_frame", 0, kMaxIndex));
  if (!(exposureScale > 0.0 && exposureScale <= kMaxExposureScale))
    fail("<expose>", "exposure_scale",
         "value " + formatShortest(exposureScale) + " is out of range " +
             formatRange(0.0, kMaxExposureScale, true));
  Image img = electronsImage(electrons, sensor);
  // As a capture's bracket and `camsim expose` scale them: a static scene's electrons are
  // linear in the exposure time.
  try {
    scaleElectrons(img, exposureScale);
  } catch (const InputError& e) {
    fail("<expose>", e.key(), e.message());
  }
  exposureTimeS *= exposureScale;
  const NoiseMode mode = noiseMode(noise);
  // An integer as seed's (found by probing: frames=True gave one frame, 2**70 and 2.0
  // pybind11's TypeError); None: one frame without the frames axis.
  const std::optional<long long> frames =
      framesArg.is_none()
          ? std::nullopt
          : std::optional(integerArg(framesArg, "<expose>", "frames", 1, kMaxExposeFrames));
  const long long n = frames.value_or(1);
  // camsim render's and expose's ISO range (found in review: iso=1e12 was exposed).
  if (iso)
    if (const std::string problem = isoRangeProblem(*iso); !problem.empty())
      fail("<expose>", "iso", problem);
  ExposureSettings settings{exposureTimeS, iso.value_or(sensor.baseIso)};
  const std::optional<DarkFrameSet> darkFrames = darkFramesFor(sensor, mode);  // as a capture's
  settings.darkFrames = darkFrames ? &*darkFrames : nullptr;
  // expose() checks the settings (InputError for ISO ≤ 0, a negative time); check them here
  // once, before the output is allocated, with this function's name.
  try {
    (void)expectedDn(0.0, sensor, settings);
  } catch (const InputError& e) {
    fail("<expose>", e.key().empty() ? "iso" : e.key(), e.message());
  }

  std::vector<py::ssize_t> shape{img.height, img.width};
  if (img.channelCount() > 1) shape.push_back(img.channelCount());
  if (frames) shape.insert(shape.begin(), static_cast<py::ssize_t>(n));
  py::array_t<std::uint16_t> out(shape);
  std::uint16_t* data = out.mutable_data();
  const std::size_t frameSize = img.pixels.size();

  tbb::task_arena arena(threads > 0 ? threads : tbb::task_arena::automatic);
  const long long group = std::max(1, arena.max_concurrency());
  for (long long first = 0; first < n; first += group) {
    const long long last = std::min(n, first + group);
    {
      py::gil_scoped_release release;
      arena.execute([&] {
        tbb::parallel_for(first, last, [&](long long f) {
          const auto raws = exposeChannels(img, sensor, settings, mode, seed,
                                           firstFrame + static_cast<std::uint64_t>(f));
          storeFrame(raws, data + static_cast<std::size_t>(f) * frameSize);
        });
      });
    }
    if (PyErr_CheckSignals() != 0) throw py::error_already_set();  // Ctrl-C: KeyboardInterrupt
  }
  return out;
}

// `camsim expose` from Python: a render's NAME_raw.exr → frames (n, h, w[, C]) and, with
// output_dir, the CLI's files (sensor/io/expose_file.h does the reading, checks and writing).
py::dict exposeFile(const py::object& pathArgument, const py::object& sensorArg,
                    const py::object& seedArg, const py::object& framesArg,
                    std::optional<double> iso, double exposureScale, const std::string& noise,
                    const py::object& outputDirArg, const py::object& threadsArg) {
  const int threads = threadCountArg(threadsArg, "<expose_file>");
  const std::filesystem::path path = pathArg(pathArgument, "<expose_file>", "path");
  const std::optional<std::string> sensor =
      sensorArg.is_none() ? std::nullopt
                          : std::optional(sensorNameOrPath(sensorArg, "<expose_file>", "sensor"));
  const std::optional<std::filesystem::path> outputDir =
      outputDirArg.is_none() ? std::nullopt
                             : std::optional(pathArg(outputDirArg, "<expose_file>", "output_dir"));
  std::optional<std::uint64_t> seed;
  if (!seedArg.is_none())
    seed = static_cast<std::uint64_t>(
        integerArg(seedArg, "<expose_file>", "seed", 0, std::numeric_limits<long long>::max()));
  ExposeFileSettings settings;
  settings.sensor = sensor.value_or("");
  settings.seed = seed;
  // Any 64-bit integer, its range the library's (which names the file); not a bool or a
  // float (pybind11's TypeError for 2**70 and 2.0; found by probing).
  settings.frames =
      integerArg(framesArg, "<expose_file>", "frames", std::numeric_limits<long long>::min(),
                 std::numeric_limits<long long>::max());
  settings.iso = iso;
  settings.exposureScale = exposureScale;
  settings.noise = noise;
  const ExposeJob job = prepareExpose(path, settings, lutsDirectory());
  const int planes = static_cast<int>(job.electrons.channels.size());
  std::vector<py::ssize_t> shape{static_cast<py::ssize_t>(job.frames), job.electrons.height,
                                 job.electrons.width};
  if (planes > 1) shape.push_back(planes);
  py::array_t<std::uint16_t> out(shape);
  std::uint16_t* data = out.mutable_data();
  const std::size_t frameSize = job.electrons.pixels.size();
  std::optional<OutputSet> outputs;
  std::vector<std::vector<std::filesystem::path>> paths;
  if (outputDir) {
    OutputSet::prepareDirectory(*outputDir);
    outputs.emplace(*outputDir);
    for (long long f = 0; f < job.frames; ++f) {
      paths.emplace_back();
      for (const std::string& name : exposeFrameFiles(job, static_cast<std::uint64_t>(f)))
        paths.back().push_back(outputs->add(name));
    }
  }
  tbb::task_arena arena(threads > 0 ? threads : tbb::task_arena::automatic);
  const long long group = std::max(1, arena.max_concurrency());
  for (long long first = 0; first < job.frames; first += group) {
    const long long last = std::min(job.frames, first + group);
    {
      py::gil_scoped_release release;
      arena.execute([&] {
        tbb::parallel_for(first, last, [&](long long f) {
          const auto frame = static_cast<std::uint64_t>(f);
          const auto raws = exposeJobFrame(job, frame);
          storeFrame(raws, data + static_cast<std::size_t>(f) * frameSize);
          if (outputs) writeExposedFrame(job, frame, raws, paths[static_cast<std::size_t>(f)]);
        });
      });
    }
    if (PyErr_CheckSignals() != 0) throw py::error_already_set();  // nothing committed
  }
  py::list files;
  if (outputs)
    for (const auto& f : outputs->commit()) files.append(f.string());
  py::dict result;
  result["raw"] = out;
  result["files"] = files;
  result["sensor"] = job.sensor;
  result["iso"] = job.exposure.iso;
  result["exposure_time_s"] = job.exposure.exposureTimeS;
  result["seed"] = job.seed;
  result["noise"] = noiseModeName(job.noise);
  return result;
}

// One raw frame as the RawImages developRaw takes: a uint16 (h, w) mosaic, a stacked
// sensor's (h, w, C) array, or a capture's dict {channel: (h, w)}.
std::vector<RawImage> rawImages(const py::object& raw, const SensorSpec& spec) {
  const auto empty = [&](py::ssize_t h, py::ssize_t w) {
    RawImage r;
    r.width = static_cast<int>(w);
    r.height = static_cast<int>(h);
    r.cfa = spec.cfa;
    r.blackLevelDn = spec.blackLevelDn;
    r.whiteLevelDn = spec.whiteLevelDn();
    r.adcBits = spec.adcBits;
    return r;
  };
  const auto plane = [&](const py::handle& h, const std::string& key) {
    const auto a = py::array_t<std::uint16_t, py::array::c_style>::ensure(h);
    if (!a || a.ndim() != 2 || a.shape(0) == 0 || a.shape(1) == 0)
      fail("<develop>", key, "expected a 2-D uint16 array (height, width) of raw DN");
    RawImage r = empty(a.shape(0), a.shape(1));
    r.dn.assign(a.data(), a.data() + a.size());
    return r;
  };
  std::vector<RawImage> raws;
  if (!spec.cfa.isStacked()) {
    raws.push_back(plane(raw, "raw"));
  } else if (py::isinstance<py::dict>(raw)) {
    const py::dict d = raw.cast<py::dict>();
    for (const std::string& c : spec.cfa.channels) {
      if (!d.contains(c))
        fail("<develop>", "raw[" + c + "]", "missing plane of the stacked sensor");
      raws.push_back(plane(d[py::str(c)], "raw[" + c + "]"));
    }
  } else {
    const auto a = py::array_t<std::uint16_t, py::array::c_style>::ensure(raw);
    const py::ssize_t c = static_cast<py::ssize_t>(spec.cfa.channels.size());
    if (!a || a.ndim() != 3 || a.shape(2) != c || a.shape(0) == 0 || a.shape(1) == 0)
      fail("<develop>", "raw",
           "expected a uint16 array (height, width, " + std::to_string(c) +
               ") or a dict of planes for the stacked sensor '" + spec.name + "'");
    for (py::ssize_t k = 0; k < c; ++k) {
      RawImage r = empty(a.shape(0), a.shape(1));
      r.dn.resize(static_cast<std::size_t>(a.shape(0) * a.shape(1)));
      for (std::size_t p = 0; p < r.dn.size(); ++p)
        r.dn[p] = a.data()[p * static_cast<std::size_t>(c) + static_cast<std::size_t>(k)];
      raws.push_back(std::move(r));
    }
  }
  for (const RawImage& r : raws) {
    const double white = spec.whiteLevelDn();
    for (std::uint16_t v : r.dn)
      if (v > white)
        fail("<develop>", "raw",
             "value " + std::to_string(v) + " above the sensor's white level " +
                 std::to_string(static_cast<int>(white)) + " DN (" + std::to_string(spec.adcBits) +
                 "-bit ADC)");
  }
  return raws;
}

IspSettings ispSettings(const std::string& whiteBalance, const std::string& illuminant,
                        const std::optional<std::vector<int>>& region,
                        const std::string& demosaic) {
  using W = IspSettings::WhiteBalance;
  IspSettings isp;
  if (const std::optional<W> wb = enumFromName<W>(whiteBalance))
    isp.whiteBalance = *wb;
  else
    fail("<develop>", "white_balance", "expected one of " + enumNameList<W>());
  // Checked here, named (found by probing: the ISP's own error said "<input>", no key).
  try {
    (void)cieIlluminant(illuminant);
  } catch (const InputError& e) {
    fail("<develop>", "illuminant", e.message());
  }
  isp.illuminant = illuminant;
  if (region) {
    if (isp.whiteBalance != W::kRegion)
      fail("<develop>", "region", "region needs white_balance='region'");
    if (region->size() != 4 || (*region)[0] < 0 || (*region)[1] < 0 || (*region)[2] < 1 ||
        (*region)[3] < 1)
      fail("<develop>", "region", "expected (x, y, width, height) in pixels, width and height ≥ 1");
    isp.region = {(*region)[0], (*region)[1], (*region)[2], (*region)[3]};
  } else if (isp.whiteBalance == W::kRegion) {
    fail("<develop>", "region", "white_balance='region' needs region=(x, y, width, height)");
  }
  // The library's table (sensor/isp/demosaic.h), with its alias "malvar-he-cutler".
  if (const std::optional<DemosaicMethod> d = enumFromName<DemosaicMethod>(demosaic))
    isp.demosaic = *d;
  else
    fail("<develop>", "demosaic", "expected one of " + enumNameList<DemosaicMethod>());
  return isp;
}

// A new float32 array holding img's pixels, (h, w, C).
py::array_t<float> toArray(const Image& img) {
  py::array_t<float> out({static_cast<py::ssize_t>(img.height), static_cast<py::ssize_t>(img.width),
                          static_cast<py::ssize_t>(img.channelCount())});
  std::memcpy(out.mutable_data(), img.pixels.data(), img.pixels.size() * sizeof(float));
  return out;
}

py::array_t<float> developFrame(const py::object& raw, const SensorSpec& sensor,
                                const std::string& whiteBalance, const std::string& illuminant,
                                const std::optional<std::vector<int>>& region,
                                const std::string& demosaic) {
  const std::vector<RawImage> raws = rawImages(raw, sensor);
  const IspSettings isp = ispSettings(whiteBalance, illuminant, region, demosaic);
  if (isp.whiteBalance == IspSettings::WhiteBalance::kRegion &&
      (std::int64_t{isp.region.x} + isp.region.width > raws[0].width ||
       std::int64_t{isp.region.y} + isp.region.height > raws[0].height))
    fail("<develop>", "region",
         "extends outside the " + std::to_string(raws[0].width) + "×" +
             std::to_string(raws[0].height) + " image");
  Image rgb;
  try {
    py::gil_scoped_release release;
    rgb = workingRgb(developRaw(raws, sensor, isp, colorCheckerCsvPath()));
  } catch (const InputError& e) {
    throw inFile(e, "<develop>");  // the ISP's errors name no file (they read "<input>")
  }
  return toArray(rgb);
}

py::array displayImage(const py::array& input, const std::string& config,
                       const std::string& display, const std::string& view, const std::string& look,
                       const std::string& dtype) {
  const auto a = py::array_t<float, py::array::c_style | py::array::forcecast>::ensure(input);
  if (!a || a.ndim() != 3 || a.shape(2) != 3 || a.shape(0) == 0 || a.shape(1) == 0)
    fail("<display>", "image", "expected a float array (height, width, 3) of ACEScg");
  if (dtype != "float32" && dtype != "uint8" && dtype != "uint16")
    fail("<display>", "dtype", "expected float32, uint8 or uint16");
  Image img(static_cast<int>(a.shape(1)), static_cast<int>(a.shape(0)), {"R", "G", "B"});
  std::memcpy(img.pixels.data(), a.data(), img.pixels.size() * sizeof(float));
  // As expose() and develop() (found by probing: NaN passed through to NaN output).
  for (std::size_t i = 0; i < img.pixels.size(); ++i)
    if (!std::isfinite(img.pixels[i]))
      fail("<display>", "image",
           "value " + formatShortest(static_cast<double>(img.pixels[i])) + " at pixel (" +
               std::to_string(i / 3 % static_cast<std::size_t>(img.width)) + ", " +
               std::to_string(i / 3 / static_cast<std::size_t>(img.width)) +
               "): expected finite ACEScg");
  const OcioProcessor ocio(config);
  Image shown;
  {
    py::gil_scoped_release release;
    shown = ocio.toDisplay(img, DisplayChoice{display, view, look});
  }
  if (dtype == "float32") return toArray(shown);
  const std::vector<py::ssize_t> shape{shown.height, shown.width, 3};
  if (dtype == "uint8") {
    const auto q = quantizeDisplay8(shown.pixels);
    py::array_t<std::uint8_t> out(shape);
    std::memcpy(out.mutable_data(), q.data(), q.size());
    return out;
  }
  const auto q = quantizeDisplay16(shown.pixels);
  py::array_t<std::uint16_t> out(shape);
  std::memcpy(out.mutable_data(), q.data(), q.size() * sizeof(std::uint16_t));
  return out;
}

}  // namespace

void bindSensorFunctions(py::module_& m) {
  py::class_<SensorSpec>(m, "Sensor",
                         R"doc(A camera sensor: EMVA 1288 parameters (docs/sensor-format.md).

Sensor(name_or_path): a preset of luts/sensors ("smartphone-1.4um", ...) or a sensor YAML
file; Sensor.of(scene): the scene's sensor. Read-only attributes in camera units:
pixel_pitch_m (m), full_well_e (e-), conversion_gain_e_per_dn (e-/DN at base ISO),
base_iso, read_noise_e (e- rms), dark_current_e_per_s (e-/s at temperature_c), dsnu_e
(e- rms), prnu (fraction), adc_bits, black_level_dn, white_level_dn (DN), cfa (name),
channels, stacked, noiseless, pattern_seed.)doc")
      .def(py::init([](const py::object& nameOrPathArg) {
             const std::string nameOrPath =
                 sensorNameOrPath(nameOrPathArg, "<Sensor>", "name_or_path");
             // An unknown preset names no file (its error said "<input>"): named here.
             try {
               return loadSensorSpec(nameOrPath, lutsDirectory());
             } catch (const InputError& e) {
               if (!e.where().file.empty()) throw;
               fail("<Sensor>", "name_or_path", e.message());
             }
           }),
           py::arg("name_or_path"))
      .def_static(
          "of",
          [](const PyScene& scene) {
            if (!scene.description.sensor)
              fail("<sensor>", "sensor", "the scene has no sensor (scene key sensor.model)");
            return scene.description.sensor->spec;
          },
          py::arg("scene"), "The sensor of a loaded scene (InputError if it has none).")
      .def_readonly("name", &SensorSpec::name)
      .def_readonly("pixel_pitch_m", &SensorSpec::pixelPitchM)
      .def_readonly("fill_factor", &SensorSpec::fillFactor)
      .def_readonly("full_well_e", &SensorSpec::fullWellE)
      .def_readonly("conversion_gain_e_per_dn", &SensorSpec::conversionGainEPerDn)
      .def_readonly("base_iso", &SensorSpec::baseIso)
      .def_readonly("read_noise_e", &SensorSpec::readNoiseE)
      .def_property_readonly("dark_current_e_per_s", &SensorSpec::darkCurrentAtTemperature)
      .def_readonly("temperature_c", &SensorSpec::temperatureC)
      .def_readonly("dsnu_e", &SensorSpec::dsnuE)
      .def_readonly("prnu", &SensorSpec::prnuFraction)
      .def_readonly("row_fpn_e", &SensorSpec::rowFpnE)
      .def_readonly("column_fpn_e", &SensorSpec::columnFpnE)
      .def_readonly("adc_bits", &SensorSpec::adcBits)
      .def_readonly("black_level_dn", &SensorSpec::blackLevelDn)
      .def_property_readonly("white_level_dn", &SensorSpec::whiteLevelDn)
      .def_readonly("pattern_seed", &SensorSpec::patternSeed)
      .def_readonly("noiseless", &SensorSpec::noiseless)
      .def_property_readonly("cfa", [](const SensorSpec& s) { return s.cfa.name; })
      .def_property_readonly("channels", [](const SensorSpec& s) { return s.cfa.channels; })
      .def_property_readonly("stacked", [](const SensorSpec& s) { return s.cfa.isStacked(); })
      .def("system_gain", ofIso<&SensorSpec::systemGain>("<system_gain>"), py::arg("iso"),
           "System gain K at an ISO, DN/e- ((iso / base_iso) / conversion gain).")
      .def("saturation_electrons",
           ofIso<&SensorSpec::saturationElectrons>("<saturation_electrons>"), py::arg("iso"),
           "Electrons at which the output saturates at an ISO: min(full well, ADC range / K).")
      .def("__repr__", [](const SensorSpec& s) { return "<camsim.Sensor '" + s.name + "'>"; });

  m.def(
      "expose", &exposeFrames, py::arg("electrons"), py::arg("sensor"), py::kw_only(),
      py::arg("seed"), py::arg("frames") = py::none(), py::arg("first_frame") = 0,
      py::arg("exposure_time") = 1.0 / 60.0, py::arg("iso") = py::none(),
      py::arg("exposure_scale") = 1.0, py::arg("noise") = "full", py::arg("threads") = 0,
      R"doc(Raw frames from noise-free electrons: photons -> electrons -> noise -> ADC (EMVA 1288).

electrons: expected photo-electrons per photosite (e-), float (height, width); a stacked
  sensor's (height, width, C) — e.g. capture(...)["electrons"], or any array of your own.
sensor: a camsim.Sensor. seed: the noise seed (temporal noise: shot, read; with
  first_frame + f the frame's stream). The fixed patterns (PRNU, DSNU, row/column FPN) are
  the sensor's own (sensor.pattern_seed): identical in every frame and for every seed.
frames: None -> one frame, uint16 (height, width[, C]); n -> uint16 (n, height, width[, C]),
  frame f drawn with frame index first_frame + f.
exposure_time (s): for the dark signal only (the electrons already hold the light).
iso: None -> the sensor's base ISO; gain K = (iso / base_iso) / conversion gain (DN/e-);
  outside a calibrated iso_table's range: camsim.InputError.
exposure_scale: X in (0, 1e6]: electrons and exposure_time times X (a static scene exposed
  X times as long; as `camsim expose --exposure-scale`).
noise: "full" (all), "photon" (shot noise only) or "none" (rounded mean).
threads: 0 -> all cores; the bytes do not depend on it.
With a capture's seed (meta["sensor"]["noise_seed"]), frame index, exposure time, ISO and
noise mode this gives that capture's raw bytes. Releases the GIL; Ctrl-C raises
KeyboardInterrupt between groups of frames. Bad input raises camsim.InputError.)doc");

  m.def("expose_file", &exposeFile, py::arg("path"), py::kw_only(), py::arg("sensor") = py::none(),
        py::arg("seed") = py::none(), py::arg("frames") = 1, py::arg("iso") = py::none(),
        py::arg("exposure_scale") = 1.0, py::arg("noise") = "full",
        py::arg("output_dir") = py::none(), py::arg("threads") = 0,
        R"doc(`camsim expose` in Python: a render's NAME_raw.exr exposed again into frames.

path: the raw EXR a render wrote (its electrons.<channel> layers: expected photo-electrons
  per photosite at that frame's exposure). sensor: a preset or YAML path (None -> the
  file's camsim:sensor, a preset: a render from a sensor description file needs it; another
  sensor only with the same CFA, photosite area and QE).
seed (None -> the file's camsim:noise_seed), iso (None -> the file's camsim:iso),
exposure_scale X (electrons and exposure time times X; a scene that moved during the
  exposure is refused unless X = 1), noise ("full", "photon", "none"), frames n: frame f
  draws the noise of (seed, f), as `camsim expose`.
output_dir: also write NAME_f<NNNN>.dng and NAME_f<NNNN>_raw.exr there, all at once (the
  CLI's bytes). Returns {"raw": uint16 (n, H, W[, C]), "files": [...], "sensor", "iso",
  "exposure_time_s", "seed", "noise"}. Bad input raises camsim.InputError naming the file
  and the key. Releases the GIL; Ctrl-C raises KeyboardInterrupt (nothing written).)doc");

  m.def("develop", &developFrame, py::arg("raw"), py::arg("sensor"), py::kw_only(),
        py::arg("white_balance") = "illuminant", py::arg("illuminant") = "D65",
        py::arg("region") = py::none(), py::arg("demosaic") = "malvar",
        R"doc(One raw frame through the ISP to scene-linear ACEScg, float32 (height, width, 3).

raw: uint16 DN (height, width) of a mosaic sensor; a stacked sensor's (height, width, C)
  array or a capture's dict {channel: (height, width)}; black level and white level are
  the sensor's. Steps (sensor/isp/isp_pipeline.h): normalise, white balance
  ("illuminant" from the CIE illuminant `illuminant`, "grey_world", or "region" over
  region=(x, y, width, height) px), demosaic ("malvar" — also "malvar-he-cutler", as
  sidecars before issue 35 wrote it — or "bilinear"), the colour matrix
  fitted from the sensor's QE on the ColorChecker under `illuminant`. 0.18 is mid-grey when
  the exposure put it there; a monochrome sensor gives grey RGB. The same settings as a
  scene's isp: block give that capture's "acescg" bytes. Releases the GIL.)doc");

  m.def("display", &displayImage, py::arg("image"), py::kw_only(), py::arg("config") = "",
        py::arg("display") = "", py::arg("view") = "", py::arg("look") = "",
        py::arg("dtype") = "float32",
        R"doc(ACEScg (height, width, 3) through OpenColorIO to a display encoding.

config: an OCIO config file ("" -> $OCIO, else camsim's luts/config.ocio); display, view,
look: the config's names ("" -> its default display, that display's default view, no
look; unknown names raise camsim.InputError listing the valid ones). dtype: "float32"
(display-encoded values, sRGB in [0, 1]), "uint8" or "uint16" (clamped, rounded code
values: a capture's "display8" and PNG bytes). Releases the GIL.)doc");
}

}  // namespace camsim::python
