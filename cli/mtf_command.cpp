#include "cli/mtf_command.h"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <memory>
#include <ostream>

#include "cli/args.h"
#include "cli/command_line.h"
#include "cli/python_script.h"
#include "sensor/io/output_set.h"
#include "sensor/measure/mtf_measurement.h"

namespace camsim {
namespace {

std::unique_ptr<CLI::App> mtfApp(MtfArgs& a) {
  auto app = newCommandApp(
      "mtf",
      "Measures the ISO 12233:2017 slanted-edge MTF (e-SFR, as Burns' sfrmat4) of IMAGE (an\n"
      "OpenEXR such as camsim's NAME.exr, or a PNG) in the region --roi, which one edge\n"
      "tilted 1-40 degrees (ideally about 5) from the vertical or horizontal crosses from\n"
      "side to side. Prints MTF50 per channel and writes into DIR:\n"
      "  mtf.csv   frequency (cycles/pixel along the edge normal, to 1; cycles/mm with\n"
      "            --pitch-um) and the MTF of each channel, normalised at zero frequency\n"
      "  mtf.json  MTF50, MTF at Nyquist, edge angle and position per channel, ROI, units\n"
      "  mtf.png   the curves (needs python3-matplotlib; skipped with a note without it)\n"
      "With --roi repeated (edges at several field heights): mtf_1.csv, mtf_1.json,\n"
      "mtf_1.png, … per region, mtf_fields.csv (each region's field height: its centre's\n"
      "distance from the image centre over the half diagonal; and MTF50) and\n"
      "mtf_fields.png (one curve per region: Y, else the first channel).\n"
      "The MTF is the image's: with a rendered or captured image, the lens times the pixel\n"
      "aperture (and sensor and ISP when they ran), as ISO reports it. docs/mtf.md.");
  app->add_option("image", a.image, "the image: OpenEXR or PNG")->type_name("IMAGE")->required();
  app->add_option("--roi", a.rois,
                  "region of interest: left, top, width, height (pixels); repeat it to "
                  "measure several edges, e.g. at several field heights")
      ->type_name("x,y,w,h")
      ->allow_extra_args(false)
      ->required();
  app->add_option("--channel", a.channel,
                  "R, G, B, Y (luminance from the file's primaries), all (R, G, B and Y; a "
                  "grey image: Y), an EXR channel by name, or several separated by commas "
                  "(default all)")
      ->type_name("C");
  app->add_option_function<std::string>(
         "--pitch-um",
         [&a](const std::string& t) {
           char* end = nullptr;
           errno = 0;
           const double v = std::strtod(t.c_str(), &end);
           if (t.empty() || end != t.c_str() + t.size() || errno != 0 || !(v > 0.0))
             throw UsageError("--pitch-um: expected a pixel pitch in micrometres, got '" + t + "'");
           a.pitchUm = v;
         },
         "pixel pitch in micrometres: frequencies also in cycles/mm")
      ->type_name("P");
  app->add_option_function<std::string>(
         "--fit-order",
         [&a](const std::string& t) {
           a.fitOrder = static_cast<int>(parseInteger("--fit-order", t, 1, 2));
         },
         "the edge fit: 1 a straight line (ISO 12233:2017, default), 2 a parabola (sfrmat4's "
         "npol = 2, for a curved edge)")
      ->type_name("1|2");
  app->add_option_function<std::string>(
         "--edge",
         [&a](const std::string& t) {
           const std::optional<EdgeOrientation> e = enumFromName<EdgeOrientation>(t);
           if (!e)
             throw UsageError("--edge: expected one of " + enumNameList<EdgeOrientation>() +
                              ", got '" + t + "'");
           a.edge = *e;
         },
         "the edge's orientation: auto (default: the pair of ROI sides that differ more), "
         "vertical or horizontal (refused if the ROI's edge runs the other way)")
      ->type_name("E");
  app->add_flag("--linear", a.linear,
                "a PNG's samples are linear (default: sRGB-decoded; EXRs are linear)");
  addOutputOption(*app, a.outputDir, "output directory (created if missing; default: out)");
  return app;
}

}  // namespace

std::string mtfUsageText() {
  MtfArgs a;
  return commandHelp(*mtfApp(a));
}

MtfArgs parseMtfArgs(const std::vector<std::string>& args) {
  MtfArgs a;
  if (!parseCommand(*mtfApp(a), args)) a.help = true;
  return a;
}

std::vector<std::filesystem::path> runMtf(const MtfArgs& args, std::ostream& out,
                                          std::ostream& log) {
  std::vector<EdgeRoi> rois;
  for (const std::string& text : args.rois) rois.push_back(parseEdgeRoi(text));
  // The output folder first, so that one that cannot be made fails before the summary is
  // printed; a folder made here is removed again if anything below fails.
  const std::filesystem::path outDir(args.outputDir);
  const NewDirectoryCleanup cleanup(outDir);
  for (const auto& stale : OutputSet::prepareDirectory(outDir))
    log << "removed " << stale.string() << " (left by a run that was killed)\n";
  const MtfImage input = readMtfImage(args.image, args.linear);
  const Image channels = selectMtfChannels(input.image, args.channel, input.yWeights, args.image);
  SfrOptions options;
  options.fitOrder = args.fitOrder;
  options.orientation = args.edge;
  options.pixelPitchM = args.pitchUm ? *args.pitchUm * 1e-6 : 0.0;
  options.source = args.image;
  std::vector<MtfMeasurement> regions;
  for (std::size_t r = 0; r < rois.size(); ++r) {
    try {
      regions.push_back(measureMtf(channels, rois[r], options));
    } catch (const InputError& e) {
      // With several, which one (found by probing: "no contrast" named none).
      if (rois.size() == 1) throw;
      throw InputError(e.where(), e.key(),
                       "--roi " + args.rois[r] + " (region " + std::to_string(r + 1) + " of " +
                           std::to_string(rois.size()) + "): " + e.message());
    }
  }
  if (input.format == "png" && !args.linear)
    log << "camsim mtf: " << args.image << " read as sRGB-encoded and decoded; a tone-mapped "
        << "picture (camsim's NAME.png) does not give the linear MTF: measure NAME.exr\n";
  for (const MtfMeasurement& m : regions) out << formatMtfSummary(m);

  OutputSet outputs(outDir);
  // One ROI: mtf.csv, mtf.json, mtf.png; several: mtf_1.csv … and mtf_fields.csv.
  const std::optional<std::string> python = pythonWithMatplotlib();
  if (!python)
    log << "camsim mtf: python3 with matplotlib not found ($CAMSIM_PYTHON or /usr/bin/python3; "
           "Debian: apt-get install python3-matplotlib): plot skipped, CSV and JSON only\n";
  std::vector<std::string> fieldPlotArgs;  // --fields PNG CSV1 JSON1 …: mtf_fields.png
  for (size_t r = 0; r < regions.size(); ++r) {
    const std::string stem = regions.size() == 1 ? "mtf" : "mtf_" + std::to_string(r + 1);
    const std::filesystem::path csv = outputs.addText(stem + ".csv", formatMtfCsv(regions[r]));
    const std::filesystem::path json = outputs.addText(stem + ".json", formatMtfJson(regions[r]));
    fieldPlotArgs.insert(fieldPlotArgs.end(), {csv.string(), json.string()});
    if (python) {
      out.flush();
      runPythonScript(*python, mtfPlotScriptFile("mtf_plot.py"),
                      {csv.string(), json.string(), outputs.add(stem + ".png").string()});
    }
  }
  if (regions.size() > 1) {
    outputs.addText("mtf_fields.csv", formatMtfFieldsCsv(regions));
    if (python) {
      fieldPlotArgs.insert(fieldPlotArgs.begin(),
                           {"--fields", outputs.add("mtf_fields.png").string()});
      runPythonScript(*python, mtfPlotScriptFile("mtf_plot.py"), fieldPlotArgs);
    }
  }
  const std::vector<std::filesystem::path> files = outputs.commit();
  for (const auto& f : files) log << "camsim mtf: wrote " << f.string() << "\n";
  return files;
}

int runMtfCommand(const std::vector<std::string>& args, std::ostream& out, std::ostream& log) {
  const MtfArgs parsed = parseMtfArgs(args);
  if (parsed.help) {
    out << mtfUsageText();
    return 0;
  }
  runMtf(parsed, out, log);
  return 0;
}

}  // namespace camsim
