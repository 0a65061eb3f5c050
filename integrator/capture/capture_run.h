// One way to run a capture for every front end (`camsim render`, `camsim dataset`,
// `camsim.capture()`): one frame or a frame sequence behind one call, progress counted over
// all frames, and the files of a run written as its frames arrive. The front ends only
// choose where the frames go (files, NumPy arrays) and what they print.
//
//   captureScene(description, options, onFrame)
//     no `frames` block → capture(),          onFrame(result, 0) once
//     a `frames` block  → captureSequence(),  onFrame(result, k) for k = 0 … count − 1
//   options.progress(done, total): tiles over the whole run; frame k's tile d of T is
//     k·T + d of count·T (one frame: the capture's own counts).
#pragma once

#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "integrator/capture/bop_writer.h"
#include "integrator/capture/capture.h"
#include "integrator/capture/capture_writer.h"
#include "integrator/capture/dataset_writer.h"

namespace camsim {

// A cancelled frame is handed on (result.cancelled) and ends the run; the summary counts
// the frames handed on (frames), those rendered (rendered) and whether it was cancelled.
// It does not check the pose exports: the caller refuses a scene whose BOP or KITTI export
// cannot be written before calling it — a writing run by making its CaptureRunWriter (which
// makes the run's models), any other with checkPoseExports (bop_writer.h).
SequenceSummary captureScene(SceneDescription description, const CaptureOptions& options,
                             const std::function<void(CaptureResult&&, int)>& onFrame);

// The files of a run into one directory: writeCapture() for each frame as it arrives and,
// for a sequence, the camera exports of all its frames (writeDatasetMetadata: cameras.json,
// transforms.json, COLMAP; docs/output.md) once the last has been written. With
// `exports: [bop]` a sequence is one BOP scene (bop_writer.h): each frame's images as it
// arrives (image id = its sequence frame number), the models and JSON files at finish().
// The pose exports' models (PoseModels) are made once, by the constructor — before anything
// renders, so a scene whose BOP or KITTI export cannot be written is an InputError then, as
// checkPoseExports — and serve every frame's BOP and KITTI files.
class CaptureRunWriter {
 public:
  // description: the run's scene, as handed to captureScene (a sequence: it has `frames`).
  CaptureRunWriter(CaptureOutputOptions out, const SceneDescription& description);
  // Not copyable: its BOP writer keeps its models' address.
  CaptureRunWriter(const CaptureRunWriter&) = delete;
  CaptureRunWriter& operator=(const CaptureRunWriter&) = delete;
  // Writes one frame (a cancelled one: only NAME.partial.exr of its finished tiles).
  WrittenCapture write(const CaptureResult& result);
  // The sequence's camera exports (nothing for one frame or after a cancelled frame) and
  // its BOP scene's models and JSON files (after a cancelled frame: of the frames done).
  std::vector<std::filesystem::path> finish();
  // Removes every file written so far (a sequence refused at a later frame: no frames
  // without their camera exports are left).
  void discard();
  // Every final file written so far, in order.
  const std::vector<std::filesystem::path>& files() const { return files_; }
  // The camera exports finish() left out, a line each with the reason (a camera model the
  // tool cannot express; dataset_writer.h).
  const std::vector<std::string>& skippedExports() const { return skipped_; }

 private:
  CaptureOutputOptions out_;
  bool sequence_;
  bool cancelled_ = false;
  std::vector<DatasetFrame> frames_;
  PoseModels models_;             // of the run's scene, made by the constructor
  std::optional<BopWriter> bop_;  // a sequence with exports: [bop]
  std::vector<std::filesystem::path> files_;
  std::vector<std::string> skipped_;
};

}  // namespace camsim
