// `camsim merge`: tile parts → assembled films → the rest of the capture → the outputs.
#include "cli/merge_command.h"

#include <memory>
#include <ostream>

#include "cli/args.h"
#include "cli/command_line.h"
#include "cli/render_command.h"
#include "integrator/capture/capture_writer.h"
#include "integrator/capture/default_scene.h"
#include "integrator/capture/progress.h"
#include "integrator/capture/tile_parts.h"
#include "sensor/base/input_error.h"
#include "sensor/io/output_set.h"

namespace camsim {
namespace {

std::unique_ptr<CLI::App> mergeApp(MergeArgs& m) {
  auto app = newCommandApp(
      "merge",
      "Assembles the parts of one frame that `camsim render SCENE --tiles k/M` rendered\n"
      "(NAME.part-k-of-M.exr, k = 0 … M-1, each exactly once, all of the same scene, seed,\n"
      "spp, overrides and camsim build), loads the scene again with the overrides the parts\n"
      "recorded, runs the rest of the capture (auto-exposure, brackets, sensor noise, ISP,\n"
      "picture) and writes into DIR the files `camsim render --reproducible` writes, byte\n"
      "for byte (docs/output.md).");
  app->add_option("parts", m.parts, "the part files")->type_name("PART...");
  addOutputOption(*app, m.outputDir, "output directory (created if missing; default: out)");
  app->add_option_function<std::string>(
         "--scene",
         [&m](const std::string& f) {
           if (f.empty()) throw UsageError("--scene needs a non-empty file name");
           m.scene = f;
         },
         "the scene file, when it is not where the parts say (their camsim:scene, as render "
         "was given it); it must be the same file (FNV-1a), and NAME.json then names FILE")
      ->type_name("FILE");
  addPictureOptions(*app, m.ocioConfig, m.display, m.view, m.look);
  app->add_flag("--aov-previews", m.aovPreviews, "as for camsim render");
  return app;
}

}  // namespace

std::string mergeUsageText() {
  MergeArgs m;
  return commandHelp(*mergeApp(m));
}

MergeArgs parseMergeArgs(const std::vector<std::string>& args) {
  MergeArgs m;
  if (!parseCommand(*mergeApp(m), args)) {
    m.help = true;
    return m;
  }
  if (m.parts.empty())
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
