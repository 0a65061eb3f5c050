// The threads that run the Python module's captures (capture_bindings.cpp) while the calling
// thread polls for Ctrl-C and reports progress. They stay alive between captures and are
// reused: Embree 3 keeps per-thread state for every device a thread creates, which a thread
// that exits never frees — a new thread per capture (std::async) leaked 8.6 KB per capture
// (measured here: rtcNewDevice/rtcReleaseDevice on a fresh std::thread, 500 times, against
// 0.0 KB on one thread that stays; python/tests/test_citizen.py). One thread per capture
// running at the same time: the pool grows to the most captures ever run at once and
// holds no other state (no scene, no result outlives its job).
#pragma once

#include <functional>
#include <future>

namespace camsim::python {

// Runs job on an idle worker thread (a new one if none is idle); the future is ready when
// it has returned (job's own exceptions are its business: capture jobs store them).
std::future<void> runOnWorkerThread(std::function<void()> job);

}  // namespace camsim::python
