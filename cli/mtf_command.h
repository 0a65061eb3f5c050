// `camsim mtf IMAGE --roi x,y,w,h [--channel R|G|B|Y|all|NAME] [--pitch-um P]
// [--fit-order 1|2] [--edge auto|vertical|horizontal] [--linear] [-o DIR]`: the ISO
// 12233:2017 slanted-edge MTF (e-SFR) of a region of an image (issue 39, part 5; docs/mtf.md).
// Reads an EXR or a PNG, measures each chosen channel
// (sensor/measure/mtf_measurement.h), prints MTF50 per channel and writes into DIR:
//   mtf.csv   frequency (cycles/px, and cycles/mm with --pitch-um), MTF per channel
//   mtf.json  MTF50 per channel, edge angle and position, ROI, source, units
//   mtf.png   the curves (scripts/mtf_plot.py, embedded; skipped with a note when
//             /usr/bin/python3 or $CAMSIM_PYTHON has no matplotlib)
// All files appear at once (OutputSet), and only after the measurement succeeded: bad
// arguments or images exit 2 with nothing written.
#pragma once

#include <filesystem>
#include <iosfwd>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "sensor/measure/slanted_edge.h"

namespace camsim {

struct MtfArgs {
  std::string image;
  std::vector<std::string> rois;  // "x,y,w,h" each (--roi once or more), parseEdgeRoi
  std::string channel = "all";    // sensor/measure/mtf_measurement.h's selection
  std::optional<double> pitchUm;
  int fitOrder = 1;
  EdgeOrientation edge = EdgeOrientation::kAuto;
  bool linear = false;  // a PNG's samples are linear (else sRGB-decoded)
  std::string outputDir = "out";
  bool help = false;
};

// args[0] == "mtf". UsageError on bad usage.
MtfArgs parseMtfArgs(const std::vector<std::string>& args);
std::string mtfUsageText();

// The embedded plot script (scripts/mtf_plot.py at build time).
std::string_view mtfPlotScriptFile(std::string_view relPath);

// Measures and writes; `out` gets the summary, `log` the files written and notes. Throws
// InputError (nothing written then). Returns the files.
std::vector<std::filesystem::path> runMtf(const MtfArgs& args, std::ostream& out,
                                          std::ostream& log);

// Entry point from main(): parses `args` (args[0] == "mtf"), runs, returns the exit code.
int runMtfCommand(const std::vector<std::string>& args, std::ostream& out, std::ostream& log);

}  // namespace camsim
