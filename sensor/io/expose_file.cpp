// Re-exposure of a render's raw EXR (expose_file.h): read, check, expose, write.
#include "sensor/io/expose_file.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <optional>
#include <string>
#include <utility>

#include "sensor/base/check.h"
#include "sensor/base/format.h"
#include "sensor/base/input_error.h"
#include "sensor/io/dark_frame_reader.h"
#include "sensor/io/exr_io.h"
#include "sensor/io/output_set.h"
#include "sensor/model/sensor_noise.h"

namespace camsim {
namespace {

const std::string kLayerPrefix = "electrons.";

[[noreturn]] void fail(const std::filesystem::path& file, const std::string& key,
                       const std::string& message) {
  throw InputError(SourceLocation{file.string(), 0, 0}, key, message);
}

std::string requiredAttribute(const std::filesystem::path& file, const Metadata& meta,
                              const std::string& key) {
  if (const std::string* v = findMetadata(meta, key)) return *v;
  fail(file, key,
       "missing header attribute: expected the raw EXR of a camsim render with a sensor "
       "(NAME_raw.exr)");
}

// A finite number (strtod's whole text) or InputError naming the attribute.
double numberAttribute(const std::filesystem::path& file, const std::string& key,
                       const std::string& text) {
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  if (text.empty() || end != text.c_str() + text.size() || !std::isfinite(v))
    fail(file, key, "expected a number, got '" + text + "'");
  return v;
}

std::optional<std::uint64_t> seedAttribute(const std::filesystem::path& file, const Metadata& m) {
  const std::string* text = findMetadata(m, "camsim:noise_seed");
  if (!text) return std::nullopt;
  // Digits only, within a scene's noise_seed range [0, 2^63 − 1] (setting_ranges.h):
  // strtoull alone took "-1" and saturated 1e20 to 2^64 − 1.
  constexpr std::uint64_t kMax = std::numeric_limits<std::int64_t>::max();
  errno = 0;
  char* end = nullptr;
  const unsigned long long v = std::strtoull(text->c_str(), &end, 10);
  if (text->empty() || text->find_first_not_of("0123456789") != std::string::npos ||
      end != text->c_str() + text->size() || errno == ERANGE || v > kMax)
    fail(file, "camsim:noise_seed", "expected an integer in [0, 2^63 - 1], got '" + *text + "'");
  return static_cast<std::uint64_t>(v);
}

// An optional attribute that must be a finite number > 0 (the lens's f-number, focal length).
std::optional<double> positiveAttribute(const std::filesystem::path& file, const Metadata& m,
                                        const std::string& key) {
  const std::string* text = findMetadata(m, key);
  if (!text) return std::nullopt;
  const double v = numberAttribute(file, key, *text);
  if (!(v > 0.0)) fail(file, key, "expected a number > 0, got '" + *text + "'");
  return v;
}

// Static or not: camsim:static_scene (1/0), else camsim:modelled's words, else refused.
void readMotion(ElectronsExr& e) {
  const std::string* modelled = findMetadata(e.metadata, "camsim:modelled");
  e.motion = modelled ? *modelled : "";
  if (const std::string* s = findMetadata(e.metadata, "camsim:static_scene")) {
    if (*s != "0" && *s != "1") fail(e.path, "camsim:static_scene", "expected 0 or 1, got " + *s);
    e.staticScene = *s == "1";
    return;
  }
  if (modelled && modelled->find("static (no time sampling)") != std::string::npos) {
    e.staticScene = true;
  } else if (modelled && modelled->find("time (") != std::string::npos) {
    e.staticScene = false;
  } else {
    fail(e.path, "camsim:static_scene",
         "missing: the file does not say whether the scene moved during the exposure "
         "(neither camsim:static_scene nor camsim:modelled); render it again with this camsim");
  }
}

// The same light on each photosite: CFA, photosite area and QE curves equal.
std::string sensorDifference(const SensorSpec& a, const SensorSpec& b) {
  if (a.cfa.name != b.cfa.name) return "CFA " + a.cfa.name + " against " + b.cfa.name;
  const double areaA = a.pixelPitchM * a.pixelPitchM * a.fillFactor;
  const double areaB = b.pixelPitchM * b.pixelPitchM * b.fillFactor;
  // Equal to a relative 1e-6, as the descriptions' decimals give them (found by probing: a
  // pitch of 1.979898987 µm at fill factor 0.5 against 1.4 µm was refused as "1.96 µm²
  // against 1.96 µm² differ", a peak QE of 0.6000001 against 0.6 too).
  const auto differ = [](double x, double y) {
    return std::abs(x - y) > 1e-6 * std::max(std::abs(x), std::abs(y));
  };
  if (differ(areaA, areaB))
    return "photosite area (pitch² × fill factor) " + formatNumber(areaA * 1e12, 10) +
           " µm² against " + formatNumber(areaB * 1e12, 10) + " µm²";
  if (a.qe.size() != b.qe.size()) return "the number of QE curves";
  for (std::size_t c = 0; c < a.qe.size(); ++c)
    for (int i = 0; i < kSpectrumSamples; ++i) {
      const double qa = static_cast<double>(a.qe[c].sample(i));
      const double qb = static_cast<double>(b.qe[c].sample(i));
      if (differ(qa, qb))
        return "QE of channel " + a.cfa.channels[c] + " at " + std::to_string(kLambdaMinNm + i) +
               " nm (" + formatNumber(qa, 8) + " against " + formatNumber(qb, 8) + ")";
    }
  return "";
}

SensorSpec chooseSensor(const ElectronsExr& in, const std::string& wanted,
                        const std::filesystem::path& lutsDir) {
  if (wanted.empty()) {
    // Found by probing: a description file named like a preset (a copy of smartphone-1.4um
    // with dark frames) was exposed with the preset.
    if (in.sensorSource == "file")
      fail(in.path, "sensor",
           "the recorded sensor '" + in.sensorName +
               "' was read from a sensor description file, not a preset (a preset of that "
               "name may differ): give --sensor with that file");
    try {
      return loadSensorSpec(in.sensorName, lutsDir);
    } catch (const InputError& e) {
      fail(in.path, "sensor",
           "the recorded sensor '" + in.sensorName +
               "' is not a preset (give --sensor, its description file): " + e.what());
    }
  }
  SensorSpec spec;
  try {
    spec = loadSensorSpec(wanted, lutsDir);
  } catch (const InputError& e) {
    throw inFile(e, in.path.string());  // an unknown preset named no file ("<input>")
  }
  if (spec.name == in.sensorName) return spec;
  // Another sensor: it must see the same electrons. The recorded one is needed to compare.
  std::optional<SensorSpec> recorded;
  try {
    recorded = loadSensorSpec(in.sensorName, lutsDir);
  } catch (const InputError&) {
  }
  if (!recorded)
    fail(in.path, "sensor",
         "sensor '" + spec.name + "' differs from the recorded sensor '" + in.sensorName +
             "', which cannot be loaded to check that their CFA and QE match");
  if (const std::string d = sensorDifference(spec, *recorded); !d.empty())
    fail(in.path, "sensor",
         "sensor '" + spec.name + "' does not see the electrons recorded for sensor '" +
             in.sensorName + "' (" + d + " differ); render the scene with '" + spec.name +
             "' instead");
  return spec;
}

}  // namespace

ElectronsExr readElectronsExr(const std::filesystem::path& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec))
    fail(path, "", "no such file (expected a render's NAME_raw.exr)");
  ExrFile exr = readExr(path);
  ElectronsExr e;
  e.path = path;
  e.metadata = std::move(exr.metadata);
  std::vector<int> layers;
  std::vector<std::string> names;
  for (std::size_t c = 0; c < exr.image.channels.size(); ++c)
    if (exr.image.channels[c].rfind(kLayerPrefix, 0) == 0) {
      layers.push_back(static_cast<int>(c));
      names.push_back(exr.image.channels[c].substr(kLayerPrefix.size()));
    }
  if (layers.empty())
    fail(path, "electrons.<channel>",
         "no electrons layer (expected a render's NAME_raw.exr: raw.DN and electrons.<channel>)");
  e.electrons = Image(exr.image.width, exr.image.height, names);
  const std::size_t n = names.size(), all = exr.image.channels.size();
  for (std::size_t p = 0;
       p < static_cast<std::size_t>(exr.image.width) * static_cast<std::size_t>(exr.image.height);
       ++p)
    for (std::size_t c = 0; c < n; ++c) {
      const float v = exr.image.pixels[p * all + static_cast<std::size_t>(layers[c])];
      if (!std::isfinite(v) || v < 0.0f)
        fail(path, kLayerPrefix + names[c],
             "value " + formatShortest(static_cast<double>(v)) + " at pixel " + std::to_string(p) +
                 ": electrons must be finite and ≥ 0");
      e.electrons.pixels[p * n + c] = v;
    }
  e.sensorName = requiredAttribute(path, e.metadata, "camsim:sensor");
  if (const std::string* source = findMetadata(e.metadata, "camsim:sensor_source"))
    e.sensorSource = *source;
  e.cfaName = requiredAttribute(path, e.metadata, "camsim:cfa");
  e.exposureTimeS = numberAttribute(path, "camsim:exposure_time_s",
                                    requiredAttribute(path, e.metadata, "camsim:exposure_time_s"));
  if (!(e.exposureTimeS > 0.0))
    fail(path, "camsim:exposure_time_s", "the exposure time must be positive");
  // Found by probing: 1e300 passed and the DNG's EXIF said 4294967295/0.
  const auto fitsTheDng = [&path](const char* key, double value, double scale, const char* tag) {
    if (value * scale > kDngMaxRational)
      fail(path, key,
           formatShortest(value) + " is beyond what the DNG's EXIF " + tag + " holds (" +
               formatShortest(kDngMaxRational / scale) + ")");
  };
  fitsTheDng("camsim:exposure_time_s", e.exposureTimeS, 1.0, "ExposureTime");
  if (const std::string* iso = findMetadata(e.metadata, "camsim:iso"))
    e.iso = numberAttribute(path, "camsim:iso", *iso);
  e.noiseSeed = seedAttribute(path, e.metadata);
  e.fNumber = positiveAttribute(path, e.metadata, "camsim:f_number");
  e.focalLengthM = positiveAttribute(path, e.metadata, "camsim:focal_length_m");
  if (e.fNumber) fitsTheDng("camsim:f_number", *e.fNumber, 1.0, "FNumber");
  if (e.focalLengthM) fitsTheDng("camsim:focal_length_m", *e.focalLengthM, 1e3, "FocalLength");
  readMotion(e);
  return e;
}

void scaleElectrons(Image& electrons, double scale) {
  if (scale == 1.0) return;
  for (std::size_t p = 0; p < electrons.pixels.size(); ++p) {
    float& v = electrons.pixels[p];
    const double scaled = static_cast<double>(v) * scale;
    if (!(scaled <= static_cast<double>(std::numeric_limits<float>::max())))
      throw InputError({}, "exposure_scale",
                       formatShortest(scale) + " scales " +
                           formatNumber(static_cast<double>(v), 6) + " electrons (pixel " +
                           std::to_string(p / electrons.channels.size()) +
                           ") beyond the float range of the output's electrons layer");
    v = static_cast<float>(scaled);
  }
}

ExposeJob prepareExpose(const std::filesystem::path& electronsExr,
                        const ExposeFileSettings& settings, const std::filesystem::path& lutsDir) {
  const std::filesystem::path& file = electronsExr;
  // The settings alone first: a bad value is named before the file is read.
  if (settings.frames < 1 || settings.frames > kMaxExposeFrames)
    fail(file, "frames",
         "value " + std::to_string(settings.frames) + " is out of range [1, " +
             std::to_string(kMaxExposeFrames) + "]");
  if (!(settings.exposureScale > 0.0 && settings.exposureScale <= kMaxExposureScale))
    fail(file, "exposure_scale",
         "value " + formatShortest(settings.exposureScale) + " is out of range " +
             formatRange(0.0, kMaxExposureScale, true));
  // render's --iso range (found by probing: --iso 1e12 was exposed and written).
  if (settings.iso)
    if (const std::string problem = isoRangeProblem(*settings.iso); !problem.empty())
      fail(file, "iso", problem);
  ExposeJob job;
  const std::optional<NoiseMode> noise = noiseModeFromName(settings.noise);
  if (!noise)
    fail(file, "noise", "unknown noise mode '" + settings.noise + "' (" + noiseModeNames() + ")");
  job.noise = *noise;
  job.frames = settings.frames;
  job.exposureScale = settings.exposureScale;

  job.input = readElectronsExr(file);
  const ElectronsExr& in = job.input;
  if (!in.staticScene && settings.exposureScale != 1.0)
    fail(file, "exposure_scale",
         "the scene moves during the exposure (" + in.motion +
             "): its expected electrons depend on the shutter interval (motion blur, rolling "
             "shutter), so they do not scale with the exposure time; render it again at the "
             "new exposure (new noise draws at --exposure-scale 1 are allowed)");
  job.sensor = chooseSensor(in, settings.sensor, lutsDir);
  const SensorSpec& spec = job.sensor;
  if (spec.cfa.name != in.cfaName)
    fail(file, "camsim:cfa",
         "the file's CFA " + in.cfaName + " is not sensor '" + spec.name + "''s " + spec.cfa.name);
  const std::size_t planes = spec.cfa.isStacked() ? spec.cfa.channels.size() : 1;
  if (in.electrons.channels.size() != planes)
    fail(file, "electrons.<channel>",
         std::to_string(in.electrons.channels.size()) + " electrons layers, sensor '" + spec.name +
             "' needs " + std::to_string(planes) +
             (spec.cfa.isStacked() ? " (a stacked sensor's planes in one file)" : ""));

  job.exposure.exposureTimeS = in.exposureTimeS * settings.exposureScale;
  if (job.exposure.exposureTimeS > kDngMaxRational)
    fail(file, "exposure_scale",
         formatShortest(settings.exposureScale) + " makes the exposure " +
             formatShortest(job.exposure.exposureTimeS) +
             " s, beyond what the DNG's EXIF ExposureTime holds (" +
             formatShortest(kDngMaxRational) + " s)");
  job.exposure.iso = settings.iso ? *settings.iso : in.iso ? *in.iso : spec.baseIso;
  try {
    (void)noiseAtIso(spec, job.exposure.iso);  // calibrated range, ISO > 0
  } catch (const InputError& e) {
    fail(file, "iso", e.message());
  }
  job.seed = settings.seed ? *settings.seed : in.noiseSeed.value_or(0);

  // Found by probing: expose drew the parametric noise for a sensor with dark frames, so
  // frame 0 was not the render's raw.
  job.darkFrames = darkFramesFor(spec, job.noise);
  job.electrons = in.electrons;
  try {
    scaleElectrons(job.electrons, settings.exposureScale);
  } catch (const InputError& e) {
    throw inFile(e, file.string());
  }
  std::string stem = file.stem().string();
  if (stem.size() > 4 && stem.compare(stem.size() - 4, 4, "_raw") == 0)
    stem.resize(stem.size() - 4);
  job.stem = stem;
  if (spec.qe.size() == 3 && !spec.cfa.isStacked())
    job.dngColor = dngColorFromQe(spec.qe, "D65",
                                  lutsDir / "spectra" / "colorchecker_classic_reflectance.csv");
  return job;
}

std::vector<RawImage> exposeJobFrame(const ExposeJob& job, std::uint64_t frame) {
  ExposureSettings exposure = job.exposure;
  exposure.darkFrames = job.darkFrames ? &*job.darkFrames : nullptr;
  return exposeChannels(job.electrons, job.sensor, exposure, job.noise, job.seed, frame);
}

std::vector<std::string> exposeFrameFiles(const ExposeJob& job, std::uint64_t frame) {
  std::string index = std::to_string(frame);
  const std::size_t width =
      std::to_string(job.frames - 1).size() < 4 ? 4 : std::to_string(job.frames - 1).size();
  if (index.size() < width) index.insert(0, width - index.size(), '0');
  const std::string base = job.stem + "_f" + index;
  if (!job.sensor.cfa.isStacked()) return {base + ".dng", base + "_raw.exr"};
  std::vector<std::string> files;
  for (const std::string& c : job.sensor.cfa.channels) files.push_back(base + "_raw_" + c + ".exr");
  return files;
}

void writeExposedFrame(const ExposeJob& job, std::uint64_t frame, const std::vector<RawImage>& raws,
                       const std::vector<std::filesystem::path>& paths) {
  const SensorSpec& spec = job.sensor;
  const Metadata replaced = {{"camsim:sensor", spec.name},
                             {"camsim:sensor_source", spec.sourceKind()},
                             {"camsim:iso", formatShortest(job.exposure.iso)},
                             {"camsim:exposure_time_s", formatShortest(job.exposure.exposureTimeS)},
                             {"camsim:noise_seed", std::to_string(job.seed)},
                             {"camsim:frame", std::to_string(frame)},
                             {"camsim:noise", noiseModeName(job.noise)},
                             {"camsim:exposure_scale", formatShortest(job.exposureScale)},
                             {"camsim:exposed_from", job.input.path.filename().string()}};
  Metadata meta;
  for (const auto& entry : job.input.metadata)
    if (!findMetadata(replaced, entry.first) && entry.first != "camsim:render_seconds")
      meta.push_back(entry);
  meta.insert(meta.end(), replaced.begin(), replaced.end());
  CAMSIM_CHECK(paths.size() == exposeFrameFiles(job, frame).size());
  if (spec.cfa.isStacked()) {
    for (std::size_t c = 0; c < raws.size(); ++c)
      writeRawExr(paths[c], raws[c], job.electrons.channel(static_cast<int>(c)), meta);
    return;
  }
  DngCapture dng;
  if (job.input.fNumber) dng.fNumber = *job.input.fNumber;
  if (job.input.focalLengthM) dng.focalLengthMm = *job.input.focalLengthM * 1e3;
  dng.dateTimeOriginal = "2000:01:01 00:00:00";  // fixed, as a render's: same seed, same bytes
  dng.exposureTimeS = job.exposure.exposureTimeS;
  dng.iso = job.exposure.iso;
  writeDng(paths[0], raws.front(), job.dngColor, meta, dng);
  writeRawExr(paths[1], raws.front(), job.electrons, meta);
}

void writeExposedFrames(const ExposeJob& job, OutputSet& outputs,
                        const std::function<void(long long)>& progress) {
  for (long long f = 0; f < job.frames; ++f) {
    const auto frame = static_cast<std::uint64_t>(f);
    std::vector<std::filesystem::path> paths;
    for (const std::string& name : exposeFrameFiles(job, frame)) paths.push_back(outputs.add(name));
    writeExposedFrame(job, frame, exposeJobFrame(job, frame), paths);
    if (progress) progress(f + 1);
  }
}

}  // namespace camsim
