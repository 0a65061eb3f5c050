#include "cli/psf_command.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <optional>
#include <ostream>

#include "cli/args.h"
#include "cli/command_line.h"
#include "integrator/scene/scene_loader.h"
#include "sensor/base/format.h"
#include "sensor/base/input_error.h"
#include "sensor/io/exr_io.h"
#include "sensor/io/json_writer.h"
#include "sensor/io/output_set.h"
#include "sensor/io/png_io.h"

namespace camsim {
namespace {

double parsePsfNumber(const std::string& flag, const std::string& text) {
  char* end = nullptr;
  errno = 0;
  const double v = std::strtod(text.c_str(), &end);
  if (text.empty() || end != text.c_str() + text.size() || errno != 0 || !std::isfinite(v))
    throw UsageError(flag + ": expected a number, got '" + text + "'");
  return v == 0.0 ? 0.0 : v;  // -0 is 0 (it named files "f-0" beside "f0")
}

// A field or wavelength as it appears in the output files' names: %g, 6 significant digits.
std::string psfNumberText(double v) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%g", v);
  return buffer;
}

std::vector<double> parsePsfList(const std::string& flag, const std::string& text) {
  std::vector<double> values;
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = text.find(',', start);
    values.push_back(parsePsfNumber(flag, text.substr(start, comma - start)));
    // Each value names files (psfEntryName): two that print alike would write the same
    // files twice.
    const std::string mine = psfNumberText(values.back());
    for (std::size_t i = 0; i + 1 < values.size(); ++i)
      if (psfNumberText(values[i]) == mine)
        throw UsageError(flag + ": " + mine + " is given twice (values name the output files, " +
                         "to 6 significant digits)");
    if (comma == std::string::npos) return values;
    start = comma + 1;
  }
}

std::unique_ptr<CLI::App> psfApp(PsfArgs& a) {
  auto app = newCommandApp(
      "psf",
      "PSF images of SCENE's camera (the thin lens of camera.aperture or the traced lens of\n"
      "camera.lens): the image on the film of an object point at the focus distance, at\n"
      "relative field height F along +x (0 the axis, 1 a corner's height: the sensor's half\n"
      "diagonal, as camsim mtf's field height) and\n"
      "wavelength λ, forward-traced over the pupil with the stop's diffraction when\n"
      "camera.aperture.diffraction is on. Writes into DIR per (F, λ) psf_f<F>_<λ>nm.exr\n"
      "(channel Y, sum 1, one pixel per cell of pitch/K) and .png (log10 over 4 decades),\n"
      "and psf.json (image height, centroid offset, RMS and 50/80 % encircled-energy radii\n"
      "in µm, vignetted fraction). docs/mtf.md, \"PSF images\".");
  app->add_option("scene", a.scene, "scene file, YAML or JSON (docs/scene-format.md)")
      ->type_name("SCENE")
      ->required();
  app->add_option_function<std::string>(
         "--field", [&a](const std::string& t) { a.fields = parsePsfList("--field", t); },
         "relative field heights in [0, 1.5], comma-separated (default 0)")
      ->type_name("F[,F...]");
  app->add_option_function<std::string>(
         "--wavelength",
         [&a](const std::string& t) { a.wavelengthsNm = parsePsfList("--wavelength", t); },
         "wavelengths in nm, [360, 830], comma-separated (default 550)")
      ->type_name("NM[,NM...]");
  app->add_option_function<std::string>(
         "--size",
         [&a](const std::string& t) {
           a.settings.size = static_cast<int>(
               parseInteger("--size", t, psf_ranges::kSizeMin, psf_ranges::kSizeMax));
         },
         "the grid's side in film pixels, [4, 512] (default 32)")
      ->type_name("PX");
  app->add_option_function<std::string>(
         "--oversample",
         [&a](const std::string& t) {
           a.settings.oversample = static_cast<int>(parseInteger(
               "--oversample", t, psf_ranges::kOversampleMin, psf_ranges::kOversampleMax));
         },
         "cells per pixel per axis, [1, 16], size × K ≤ 2048 (default 4)")
      ->type_name("K");
  app->add_option_function<std::string>(
         "--rays",
         [&a](const std::string& t) {
           a.settings.rays = parseInteger("--rays", t, psf_ranges::kRaysMin, psf_ranges::kRaysMax);
         },
         "rays traced per entry, [1000, 100000000] (default 1000000)")
      ->type_name("N");
  app->add_option_function<std::string>(
         "--seed",
         [&a](const std::string& t) {
           a.settings.seed = static_cast<std::uint64_t>(parseInteger("--seed", t, 0, INT64_MAX));
         },
         "random stream (default 0): the same seed gives the same files")
      ->type_name("S");
  app->add_option_function<std::string>(
         "--object-distance",
         [&a](const std::string& t) {
           a.settings.objectDistance = parsePsfNumber("--object-distance", t);
         },
         "the object point's distance in m (from the lens, or a traced lens's entrance pupil); "
         "default: the camera's focus distance")
      ->type_name("M");
  addOutputOption(*app, a.outputDir, "output directory (created if missing; default: out)");
  return app;
}

// The library's InputError about a setting as a UsageError naming its option
// ("object_distance" → --object-distance).
[[noreturn]] void throwAsOption(const InputError& e) {
  std::string flag = "--" + e.key();
  std::replace(flag.begin(), flag.end(), '_', '-');
  throw UsageError(flag + ": " + e.message());
}

// Every entry's settings, each checked by the library (the ranges, before the scene loads).
std::vector<PsfSettings> psfEntries(const PsfArgs& a) {
  std::vector<PsfSettings> entries;
  for (double field : a.fields)
    for (double lambda : a.wavelengthsNm) {
      PsfSettings s = a.settings;
      s.field = field;
      s.wavelengthNm = lambda;
      try {
        checkPsfSettings(s);
      } catch (const InputError& e) {
        throwAsOption(e);
      }
      entries.push_back(s);
    }
  return entries;
}

// The preview: log10 of the cell over the peak, 4 decades to black, each cell a square of
// `zoom` pixels (the picture at least 256 px wide).
void writePsfPreview(const std::filesystem::path& path, const PsfImage& psf) {
  const int n = psf.cells, zoom = std::max(1, 256 / n), w = n * zoom;
  const double peak = *std::max_element(psf.energy.begin(), psf.energy.end());
  std::vector<std::uint8_t> rgb(static_cast<size_t>(w) * static_cast<size_t>(w) * 3, 0);
  for (int y = 0; y < w; ++y)
    for (int x = 0; x < w; ++x) {
      const double e = psf.energy[static_cast<size_t>(y / zoom) * static_cast<size_t>(n) +
                                  static_cast<size_t>(x / zoom)];
      const double v =
          e > 0.0 && peak > 0.0 ? std::clamp(1.0 + std::log10(e / peak) / 4.0, 0.0, 1.0) : 0.0;
      const auto grey = static_cast<std::uint8_t>(std::lround(255.0 * v));
      const size_t i =
          (static_cast<size_t>(y) * static_cast<size_t>(w) + static_cast<size_t>(x)) * 3;
      rgb[i] = rgb[i + 1] = rgb[i + 2] = grey;
    }
  writePng8(path, w, w, rgb, false);
}

JsonObject psfEntryJson(const PsfImage& psf, const std::string& name) {
  JsonObject j;
  j.set("file", name + ".exr")
      .set("field", psf.settings.field)
      .set("image_height_mm", psf.imageHeight * 1e3)
      .set("wavelength_nm", psf.settings.wavelengthNm)
      .set("object_distance_m", psf.objectDistance)
      .set("working_f_number", psf.workingFNumber)
      .set("centroid_offset_um", std::vector<double>{psf.centroidX * 1e6, psf.centroidY * 1e6})
      .set("rms_radius_um", psf.rmsRadius * 1e6)
      .set("ee50_radius_um", psf.encircled50 * 1e6)
      .set("ee80_radius_um", psf.encircled80 * 1e6)
      .set("lost_fraction", psf.lostFraction)
      .set("outside_grid_fraction", psf.outsideFraction)
      .set("rays", static_cast<double>(psf.settings.rays))
      .set("rays_landed", static_cast<double>(psf.landed))
      .set("cells", static_cast<double>(psf.cells))
      .set("cell_um", std::vector<double>{psf.cellWidth * 1e6, psf.cellHeight * 1e6});
  return j;
}

}  // namespace

std::string psfEntryName(double field, double wavelengthNm) {
  return "psf_f" + psfNumberText(field) + "_" + psfNumberText(wavelengthNm) + "nm";
}

std::string psfUsageText() {
  PsfArgs a;
  return commandHelp(*psfApp(a));
}

PsfArgs parsePsfArgs(const std::vector<std::string>& args) {
  PsfArgs a;
  if (!parseCommand(*psfApp(a), args)) {
    a.help = true;
    return a;
  }
  psfEntries(a);  // range-checks every value before anything is loaded or written
  return a;
}

std::vector<std::filesystem::path> runPsf(const PsfArgs& args, std::ostream& out,
                                          std::ostream& log) {
  const std::vector<PsfSettings> entries = psfEntries(args);
  const SceneDescription scene = loadScene(args.scene);
  const PhysicalCamera camera = [&] {
    try {
      return PhysicalCamera(scene.camera);
    } catch (const InputError& e) {  // a lens passing no light: the scene's
      throw inFile(e, scene.sourceFile);
    }
  }();
  std::vector<PsfImage> images;
  for (const PsfSettings& s : entries) {
    // The settings against this camera (a distance inside its focal length, a field off its
    // film): the same options' errors, found once the camera is known.
    try {
      images.push_back(computePsf(camera, s));
    } catch (const InputError& e) {
      if (e.where().file.empty()) throwAsOption(e);
      throw;
    }
    const PsfImage& p = images.back();
    out << psfEntryName(s.field, s.wavelengthNm) << ": field " << s.field << " (h "
        << formatFixed(p.imageHeight * 1e3, 3) << " mm), " << s.wavelengthNm << " nm: centroid ("
        << formatFixed(p.centroidX * 1e6, 3) << ", " << formatFixed(p.centroidY * 1e6, 3)
        << ") µm, RMS " << formatFixed(p.rmsRadius * 1e6, 2) << " µm, EE50 "
        << formatFixed(p.encircled50 * 1e6, 2) << " µm, EE80 "
        << formatFixed(p.encircled80 * 1e6, 2) << " µm, lost "
        << formatFixed(p.lostFraction * 100.0, 1) << " %\n";
  }

  const std::filesystem::path outDir(args.outputDir);
  for (const auto& stale : OutputSet::prepareDirectory(outDir))
    log << "removed " << stale.string() << " (left by a run that was killed)\n";
  OutputSet outputs(outDir);
  std::vector<JsonObject> json;
  for (const PsfImage& p : images) {
    const std::string name = psfEntryName(p.settings.field, p.settings.wavelengthNm);
    Image y(p.cells, p.cells, {"Y"});
    for (size_t i = 0; i < p.energy.size(); ++i) y.pixels[i] = static_cast<float>(p.energy[i]);
    // Shortest round-trip text, as the JSON (std::to_string wrote a field of 1e-7 as
    // "0.000000").
    const Metadata meta = {{"camsim:psf_field", formatShortest(p.settings.field)},
                           {"camsim:psf_wavelength_nm", formatShortest(p.settings.wavelengthNm)},
                           {"camsim:psf_cell_um", formatShortest(p.cellWidth * 1e6) + " x " +
                                                      formatShortest(p.cellHeight * 1e6)},
                           {"camsim:scene", args.scene}};
    writeExr(outputs.add(name + ".exr"), y, meta, std::nullopt);
    writePsfPreview(outputs.add(name + ".png"), p);
    json.push_back(psfEntryJson(p, name));
  }
  JsonObject root, units;
  units.set("field", "image height / (sensor diagonal / 2), along +x (right)")
      .set("image_height", "mm on the film from the sensor's centre")
      .set("offsets", "µm on the film, x right, y up, from the chief ray's image point")
      .set("radii", "µm about the centroid; RMS and the radii enclosing 50 % and 80 %")
      .set("lost_fraction", "of the light through the stop's opening, blocked by a rim")
      .set("exr", "channel Y: energy per cell (pitch / oversample), sum 1, row 0 at the top")
      .set("png", "log10(cell / peak) over 4 decades, black below");
  root.set("format", "camsim-psf")
      .set("scene", args.scene)
      .set("lens",
           camera.lensCamera() ? scene.camera.lens->prescription.source : std::string("thin lens"))
      .setInteger("seed", args.settings.seed)
      .set("units", units)
      .set("entries", json);
  outputs.addText("psf.json", root.str() + "\n");
  const std::vector<std::filesystem::path> files = outputs.commit();
  for (const auto& f : files) log << "camsim psf: wrote " << f.string() << "\n";
  return files;
}

int runPsfCommand(const std::vector<std::string>& args, std::ostream& out, std::ostream& log) {
  const PsfArgs parsed = parsePsfArgs(args);
  if (parsed.help) {
    out << psfUsageText();
    return 0;
  }
  runPsf(parsed, out, log);
  return 0;
}

}  // namespace camsim
