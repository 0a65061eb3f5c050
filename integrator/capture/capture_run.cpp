#include "integrator/capture/capture_run.h"

#include <algorithm>
#include <system_error>
#include <utility>

#include "integrator/capture/kitti_writer.h"
#include "sensor/base/input_error.h"

namespace camsim {

SequenceSummary captureScene(SceneDescription description, const CaptureOptions& options,
                             const std::function<void(CaptureResult&&, int)>& onFrame) {
  if (!description.frames) {
    CaptureResult result = capture(std::move(description), options);
    SequenceSummary summary;
    summary.frames = 1;
    summary.rendered = result.cancelled ? 0 : 1;
    summary.cancelled = result.cancelled;
    onFrame(std::move(result), 0);
    return summary;
  }
  const int count = description.frames->count;
  int frame = 0;  // the frame being rendered: onFrame of frame k runs before frame k + 1
  CaptureOptions perFrame = options;
  if (options.progress)
    perFrame.progress = [&frame, count, &progress = options.progress](int done, int total) {
      progress(frame * total + done, count * total);
    };
  const int first = description.frames->first;
  try {
    return captureSequence(std::move(description), perFrame,
                           [&frame, &onFrame](CaptureResult&& result, int k) {
                             onFrame(std::move(result), k);
                             frame = k + 1;
                           });
  } catch (const InputError& e) {
    // Bad input found only at a later frame (its rendered raw cannot be white-balanced):
    // which frame (found by probing: the message did not say).
    if (frame == 0) throw;
    throw InputError(e.where(), e.key(),
                     "at frame " + std::to_string(first + frame) + " (frame " +
                         std::to_string(frame + 1) + " of " + std::to_string(count) +
                         "): " + e.message());
  }
}

void CaptureRunWriter::discard() {
  for (const std::filesystem::path& f : files_) {
    std::error_code ignored;
    std::filesystem::remove(f, ignored);
  }
  files_.clear();
}

// The models of the scene before it renders are its frames': a capture changes its camera,
// name and sensor, never its shapes.
CaptureRunWriter::CaptureRunWriter(CaptureOutputOptions out, const SceneDescription& description)
    : out_(std::move(out)), sequence_(description.frames.has_value()), models_(description) {}

WrittenCapture CaptureRunWriter::write(const CaptureResult& result) {
  WrittenCapture written = writeCapture(result, out_, &models_);
  files_.insert(files_.end(), written.files.begin(), written.files.end());
  skipped_.insert(skipped_.end(), written.skipped.begin(), written.skipped.end());
  if (result.cancelled) {
    cancelled_ = true;
    return written;
  }
  if (!sequence_) return written;
  const SceneDescription& d = result.description;
  // The image id of both exports: the frame's sequence frame number.
  const int image = (d.frames ? d.frames->first : 0) + static_cast<int>(frames_.size());
  if (d.exportsTo(ExportFormat::kBop)) {
    if (!bop_) bop_.emplace(out_.directory, out_.datasetItem, models_);
    for (auto& f : bop_->addFrame(result, image)) {
      files_.push_back(f);
      written.files.push_back(std::move(f));
    }
  }
  if (d.exportsTo(ExportFormat::kKitti)) {
    std::vector<std::string> notes;
    for (auto& f : writeKittiFrame(result, models_.ownOfShape(), out_.directory, image, &notes)) {
      files_.push_back(f);
      written.files.push_back(std::move(f));
    }
    // Each note once for the sequence, not once per frame.
    for (std::string& n : notes)
      if (std::find(skipped_.begin(), skipped_.end(), n) == skipped_.end())
        skipped_.push_back(std::move(n));
  }
  frames_.push_back(datasetFrame(result));
  return written;
}

std::vector<std::filesystem::path> CaptureRunWriter::finish() {
  if (!sequence_) return {};
  // A cancelled sequence has no camera exports, but its BOP scene is finished over the
  // frames done: bop/ never holds images without their scene_gt / scene_camera entries.
  std::vector<std::filesystem::path> written;
  if (!cancelled_) written = writeDatasetMetadata(frames_, out_.directory, &skipped_);
  if (bop_) {
    for (auto& f : bop_->finish()) written.push_back(std::move(f));
    skipped_.insert(skipped_.end(), bop_->skipped().begin(), bop_->skipped().end());
  }
  files_.insert(files_.end(), written.begin(), written.end());
  return written;
}

}  // namespace camsim
