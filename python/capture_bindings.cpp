// camsim.capture(scene) and Scene.render(): the capture library call (integrator/capture)
// on a worker thread while the calling thread, holding the GIL only for moments, polls for
// signals every 50 ms (Ctrl-C: the capture is cancelled — the render checks every 64
// samples of a pixel — and KeyboardInterrupt raised; nothing is written, ever) and reports
// progress. The arrays come back without a copy (capture_arrays.h).
#include <chrono>
#include <future>
#include <iterator>
#include <optional>

#include "integrator/capture/capture_run.h"
#include "integrator/capture/progress.h"
#include "integrator/capture/resource_guard.h"
#include "python/bindings.h"
#include "python/capture_arrays.h"
#include "python/worker_threads.h"
#include "sensor/base/threads.h"

namespace camsim::python {
namespace {

namespace py = pybind11;

// One capture's shared state between the worker and the calling thread.
struct CaptureJob {
  SceneDescription description;
  PictureSettings picture;
  int threads = 0;
  std::optional<double> maxMemoryGb;  // none: the default limit (resource_guard.h)
  std::atomic<bool> cancel{false};
  std::atomic<int> done{0}, total{0};                    // tiles over all frames (captureScene)
  std::vector<std::shared_ptr<CaptureBuffers>> results;  // one per frame, in order
  std::exception_ptr error;
  // The Scene's built renderable scene, lent for this capture (null: reuse=False, build
  // afresh and keep nothing); a sequence builds its own for all its frames.
  std::unique_ptr<SceneCache> built;
};

std::shared_ptr<CaptureBuffers> keep(CaptureResult&& r, const PictureSettings& picture) {
  auto b = std::make_shared<CaptureBuffers>();
  b->result = std::move(r);
  deriveBuffers(*b, picture);
  return b;
}

// The worker: captureScene() (one frame or a sequence); no Python here.
void runJob(CaptureJob& job) {
  try {
    CaptureOptions options;
    options.threads = job.threads;
    options.cancel = &job.cancel;
    options.progress = [&job](int done, int total) {
      job.total = total;
      job.done = done;
    };
    options.sceneCache = job.built.get();
    // No files here, but a scene whose BOP or KITTI export cannot be written, or that needs
    // more memory than the limit, is refused before it renders, as `camsim render` refuses
    // it (found by probing: a 32768 × 8192 capture raised MemoryError std::bad_alloc).
    checkMemoryLimit(job.description, job.maxMemoryGb, "max_memory_gb");
    checkPoseExports(job.description);
    captureScene(std::move(job.description), options, [&job](CaptureResult&& r, int) {
      if (!r.cancelled) job.results.push_back(keep(std::move(r), job.picture));
    });
  } catch (...) {
    job.error = std::current_exception();
  }
}

// The override keyword arguments, in overrides.h's table order (every key of the table).
constexpr const char* kOverrideKwargs[] = {
    "sensor",          "spp",      "seed", "target_error", "time_limit_s", "adaptive_threshold",
    "exposure_time_s", "f_number", "iso",  "noise",        "noise_seed",   "pose",
    "projection",      "guiding"};

py::object runCapture(PyScene& scene, const py::object& threadsArg, const py::object& progress,
                      const std::string& display, const std::string& view, const std::string& look,
                      const std::string& ocioConfig, bool reuse, const py::object& sensor,
                      const py::object& spp, const py::object& seed, const py::object& targetError,
                      const py::object& timeLimitS, const py::object& adaptiveThreshold,
                      const py::object& exposureTimeS, const py::object& fNumber,
                      const py::object& iso, const py::object& noise, const py::object& noiseSeed,
                      const py::object& pose, const py::object& projection,
                      const py::object& guiding, const py::object& maxMemoryGb) {
  const int threads = threadCountArg(threadsArg, "<capture>");
  std::optional<double> memoryLimit;
  if (!maxMemoryGb.is_none()) {
    // A real number (numbers.Real: int, float, NumPy's float32 as the overrides take; not a
    // bool): a complex or an int past a double raised TypeError or OverflowError (found in
    // review), and np.float32 was refused (found by probing).
    const bool real = py::isinstance(maxMemoryGb, py::module_::import("numbers").attr("Real")) &&
                      !PyBool_Check(maxMemoryGb.ptr());
    if (!real) throw InputError({"<capture>", 0, 0}, "max_memory_gb", "expected a number of GB");
    double gb = PyFloat_AsDouble(maxMemoryGb.ptr());
    if (PyErr_Occurred()) {  // an int past a double: refused below
      PyErr_Clear();
      gb = -1.0;
    }
    memoryLimit = checkMaxMemoryGb(gb, {"<capture>", 0, 0}, "max_memory_gb");
  }
  // For this capture only (the Scene keeps its settings), checked before anything runs.
  Overrides overrides;
  const py::object* values[] = {
      &sensor,  &spp, &seed,  &targetError, &timeLimitS, &adaptiveThreshold, &exposureTimeS,
      &fNumber, &iso, &noise, &noiseSeed,   &pose,       &projection,        &guiding};
  static_assert(std::size(values) == std::size(kOverrideKwargs));
  for (std::size_t i = 0; i < std::size(values); ++i)
    if (!values[i]->is_none())
      setOverrideFromPython(overrides, *findOverrideSetting(kOverrideKwargs[i]), *values[i],
                            kOverrideKwargs[i]);
  SceneDescription description = scene.description;
  applyOverrides(description, overrides, {"<override>", 0, 0});
  auto job = std::make_shared<CaptureJob>();
  // Taken with the GIL held: a capture of this Scene running at the same time (another
  // Python thread) finds none and builds its own.
  if (reuse) job->built = scene.built ? std::move(scene.built) : std::make_unique<SceneCache>();
  scene.built.reset();  // reuse=False keeps nothing either
  // Given back however this returns (still valid after a cancel or an error; a Scene that
  // failed to build is not in it); of two captures at once, the last to finish wins.
  struct GiveBack {
    PyScene& scene;
    CaptureJob& job;
    ~GiveBack() {
      if (job.built) scene.built = std::move(job.built);
    }
  } giveBack{scene, *job};
  job->picture = PictureSettings{ocioConfig, DisplayChoice{display, view, look}};
  job->threads = threads;
  job->maxMemoryGb = memoryLimit;
  const bool sequence = description.frames.has_value();
  std::optional<ProgressBar> bar;  // on stderr, drawn only when it is a terminal
  if (progress.is_none()) bar.emplace("rendering " + description.name);
  bool stopped = false;  // a Python exception (KeyboardInterrupt, the callback's) is pending
  {
    py::gil_scoped_release release;
    job->description = std::move(description);  // the worker's copy (meshes copied in memory)
    checkPictureSettings(job->picture);         // a bad config or display fails before rendering
    std::future<void> worker = runOnWorkerThread([job] { runJob(*job); });
    int reported = -1;
    while (worker.wait_for(std::chrono::milliseconds(50)) != std::future_status::ready) {
      py::gil_scoped_acquire acquire;
      if (PyErr_CheckSignals() != 0) {
        stopped = true;
        break;
      }
      const int all = job->total, now = job->done;  // over all frames (captureScene)
      if (all == 0 || now == reported) continue;
      reported = now;
      if (bar) {
        bar->update(now, all);
      } else {
        try {
          progress(now, all);
        } catch (py::error_already_set& e) {
          e.restore();
          stopped = true;
          break;
        }
      }
    }
    if (stopped) job->cancel = true;
    worker.wait();  // a cancelled capture returns within 64 samples of the pixels in flight
  }
  if (bar) bar->finish();
  if (stopped) throw py::error_already_set();
  if (job->error) std::rethrow_exception(job->error);
  if (!bar && job->total > 0) progress(job->total.load(), job->total.load());
  if (!sequence) return captureDict(job->results.front());
  py::list frames;
  for (const auto& b : job->results) frames.append(captureDict(b));
  return frames;
}

constexpr const char* kCaptureDoc =
    R"doc(Captures the scene as `camsim render` does (render → auto-exposure → brackets → expose →
develop → display), writing nothing, and returns a dict of NumPy arrays that view camsim's
own buffers (no copy; each array keeps the whole capture alive, docs/python.md):

  xyz        float32 (H, W, 3)  CIE XYZ per photosite × 683 lm/W (Y: lm·s), NAME.exr's XYZ
  rgb        float32 (H, W, 3)  linear Rec.709, same scale (strided view), NAME.exr's R, G, B
  acescg     float32 (H, W, 3)  scene-linear ACEScg, 0.18 mid-grey (with a sensor: developed)
  display    float32 (H, W, 3)  through OpenColorIO's display/view/look (sRGB: 0–1)
  display8   uint8   (H, W, 3)  display quantised: NAME.png's pixels
  aovs       dict layer → array (depth (H, W) m, P (H, W, 3) m, N …, instance (H, W) uint32 …)
  spp        float32 (H, W)     adaptive sampling only: each pixel's samples (NAME.exr's spp)
with a sensor also
  electrons  float32 (H, W, C)  expected e⁻ per photosite of the developed frame, noise-free
  raw        uint16  (H, W)     its digital numbers (DN; a stacked sensor: dict plane → array)
  brackets   list per bracket of {ev, exposure_time_s, frame_index, white_balance_gains,
             clipped_fraction, electrons, raw}
  sensor_film float32 (H, W, C) expected e⁻ at the scene's own exposure time
and
  meta       dict: NAME.json's content (scene, input files, render incl. "modelled", camera
             with intrinsics, sensor, isp), "pose" (world_from_camera_opencv, intrinsics,
             exposure), "color" (the OCIO config, display, view, look)

A scene with a frames block returns a list of such dicts, one per frame.
threads: worker threads (0: all); the arrays are the same for any count. progress: called
as progress(done, total) with the GIL held, at most every 50 ms (no callback: a progress
bar on stderr when it is a terminal). The GIL is released while rendering; Ctrl-C cancels
the capture and raises KeyboardInterrupt (within about 0.1 s, at any spp).
display/view/look/ocio_config: as camsim render's --display, --view, --look, --ocio-config.
reuse: render on the renderable scene (Embree BVH, materials, lights) the Scene's previous
capture built, when only its camera, exposure, f-number, ISO, sensor, seeds or spp changed
(the same bytes as a fresh build; meta["scene_reused"] says whether it was); False: build
it afresh and keep nothing.
sensor, spp, seed, target_error, time_limit_s, adaptive_threshold, exposure_time_s, f_number,
iso, noise, noise_seed, pose, projection, guiding: overrides for this capture only (the Scene
keeps its own settings), the keys, ranges and
messages of load()'s overrides dict and camsim render's flags (integrator/scene/overrides.h):
e.g. capture(scene, spp=16, seed=3, f_number=2.8). None: the scene's value. projection is the
camera model, camera.projection's map as a dict or YAML/JSON text, e.g.
projection={"model": "kannala_brandt", "k1": 0.02} (docs/camera.md).
Raises camsim.InputError for a bad override, a bad display choice or a file a capture reads
again.)doc";

}  // namespace

void bindCaptureFunctions(py::module_& m) {
  m.def("capture", &runCapture, py::arg("scene"), py::kw_only(), py::arg("threads") = 0,
        py::arg("progress") = py::none(), py::arg("display") = "", py::arg("view") = "",
        py::arg("look") = "", py::arg("ocio_config") = "", py::arg("reuse") = true,
        py::arg("sensor") = py::none(), py::arg("spp") = py::none(), py::arg("seed") = py::none(),
        py::arg("target_error") = py::none(), py::arg("time_limit_s") = py::none(),
        py::arg("adaptive_threshold") = py::none(), py::arg("exposure_time_s") = py::none(),
        py::arg("f_number") = py::none(), py::arg("iso") = py::none(),
        py::arg("noise") = py::none(), py::arg("noise_seed") = py::none(),
        py::arg("pose") = py::none(), py::arg("projection") = py::none(),
        py::arg("guiding") = py::none(), py::arg("max_memory_gb") = py::none(), kCaptureDoc);
  py::object scene = m.attr("Scene");
  scene.attr("render") = py::cpp_function(
      &runCapture, py::name("render"), py::is_method(scene), py::kw_only(), py::arg("threads") = 0,
      py::arg("progress") = py::none(), py::arg("display") = "", py::arg("view") = "",
      py::arg("look") = "", py::arg("ocio_config") = "", py::arg("reuse") = true,
      py::arg("sensor") = py::none(), py::arg("spp") = py::none(), py::arg("seed") = py::none(),
      py::arg("target_error") = py::none(), py::arg("time_limit_s") = py::none(),
      py::arg("adaptive_threshold") = py::none(), py::arg("exposure_time_s") = py::none(),
      py::arg("f_number") = py::none(), py::arg("iso") = py::none(), py::arg("noise") = py::none(),
      py::arg("noise_seed") = py::none(), py::arg("pose") = py::none(),
      py::arg("projection") = py::none(), py::arg("guiding") = py::none(),
      py::arg("max_memory_gb") = py::none(),
      ("scene.render(...) is camsim.capture(scene, ...):\n\n" + std::string(kCaptureDoc)).c_str());
}

}  // namespace camsim::python
