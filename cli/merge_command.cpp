// `camsim merge`: tile parts → assembled films → the rest of the capture → the outputs.
#include "cli/merge_command.h"

#include <ostream>

#include "cli/args.h"
#include "cli/progress.h"
#include "cli/render_command.h"
#include "integrator/capture/capture_writer.h"
#include "integrator/capture/tile_parts.h"
#include "sensor/base/input_error.h"
#include "sensor/io/output_set.h"

namespace camsim {
std::string mergeUsageText() {
  return "usage: camsim merge PART... [-o DIR] [--scene FILE] [--ocio-config FILE]\n"
         "                    [--display D] [--view V] [--look L] [--aov-previews]\n"
         "\n"
         "merge  assembles the parts of one frame that `camsim render SCENE --tiles k/M`\n"
         "       rendered (NAME.part-k-of-M.exr, k = 0 … M-1, each exactly once, all of the\n"
         "       same scene, seed, spp, overrides and camsim build), loads the scene again,\n"
         "       runs the rest of the capture (auto-exposure, brackets, sensor noise, ISP,\n"
         "       picture) and writes into DIR (default: out/) the files `camsim render\n"
         "       --reproducible` writes, byte for byte (docs/output.md)\n"
         "  -o, --output DIR   output directory (created if missing)\n"
         "  --scene FILE       the scene file, when it is not where the parts say (their\n"
         "                     camsim:scene, as render was given it); it must be the same\n"
         "                     file (FNV-1a), and NAME.json then names FILE\n"
         "  --ocio-config FILE, --display D, --view V, --look L, --aov-previews\n"
         "                     as for camsim render (camsim --help)\n";
}

MergeArgs parseMergeArgs(const std::vector<std::string>& args) {
  MergeArgs m;
  for (std::size_t i = 1; i < args.size(); ++i) {
    const std::string& a = args[i];
    auto value = [&]() -> const std::string& {
      if (i + 1 >= args.size()) throw UsageError(a + " needs a value");
      return args[++i];
    };
    if (a == "--help" || a == "-h") {
      m.help = true;
    } else if (a == "-o" || a == "--output") {
      m.outputDir = value();
      if (m.outputDir.empty()) throw UsageError(a + " needs a non-empty directory");
    } else if (a == "--scene") {
      m.scene = value();
      if (m.scene->empty()) throw UsageError(a + " needs a non-empty file name");
    } else if (a == "--ocio-config") {
      m.ocioConfig = value();
    } else if (a == "--display") {
      m.display = value();
    } else if (a == "--view") {
      m.view = value();
    } else if (a == "--look") {
      m.look = value();
    } else if (a == "--aov-previews") {
      m.aovPreviews = true;
    } else if (!a.empty() && a[0] == '-') {
      throw UsageError("unknown option '" + a + "' (try 'camsim merge --help')");
    } else {
      m.parts.push_back(a);
    }
  }
  if (!m.help && m.parts.empty())
    throw UsageError("merge needs the part files of a render --tiles (try 'camsim merge --help')");
  return m;
}

std::vector<std::filesystem::path> runMerge(const MergeArgs& args, std::ostream& log) {
  const std::vector<std::filesystem::path> files(args.parts.begin(), args.parts.end());
  AssembledTiles tiles = assembleTileParts(files);
  const TilePartHeader header = tiles.header;  // kept: the tiles move into the capture
  RenderArgs render;
  render.overrides = header.overrides;  // as the parts recorded them (data, not flags)
  if (args.scene)
    render.scene = *args.scene;
  else if (header.scene != kDefaultSceneName)
    render.scene = header.scene;
  const double partSeconds = tiles.renderSeconds;
  CaptureResult result = mergedCapture(std::move(tiles), loadRenderScene(render));

  CaptureOutputOptions out{
      args.outputDir, {args.ocioConfig, {args.display, args.view, args.look}}, args.aovPreviews};
  out.reproducible = true;
  checkPictureSettings(out.picture);  // a bad config or display/view/look: nothing written
  for (const auto& stale : OutputSet::prepareDirectory(out.directory))
    log << "removed " << stale.string() << " (left by a run that was killed)\n";
  finishCapture(result);
  printCaptureNotes(result, log);
  const WrittenCapture written = writeCapture(result, out);
  for (const auto& f : written.removed)
    log << "removed " << f.string() << " of an interrupted run\n";
  log << "merged " << header.tileCount << (header.tileCount == 1 ? " part" : " parts") << " of "
      << header.name << ": " << header.resolution.x << "x" << header.resolution.y << ", "
      << renderTileCount(header.resolution) << " tiles, " << header.spp << " spp"
      << (partSeconds > 0.0 ? ", rendered in " + formatSeconds(partSeconds) + " in all" : "")
      << ", rejected samples (NaN/Inf): " << result.stats.rejectedSamples << "\n";
  for (const auto& f : written.files) log << "wrote " << f.string() << "\n";
  return written.files;
}

int runMergeCommand(const std::vector<std::string>& args, std::ostream& out, std::ostream& log) {
  const MergeArgs parsed = parseMergeArgs(args);
  if (parsed.help) {
    out << mergeUsageText();
    return 0;
  }
  runMerge(parsed, log);
  return 0;
}

}  // namespace camsim
