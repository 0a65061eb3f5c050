// libFuzzer harness: raw DNG files → camsim::readRawDng (sensor/io/dark_frame_reader.h),
// the dark-frame reader. libtiff reads from a path, so each input is written to a file
// first. Bad input must end in InputError; anything else (crash, sanitizer report, a frame
// whose size disagrees with its data) is a finding.
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <string>

#include "fuzz/fuzz_check.h"
#include "sensor/base/input_error.h"
#include "sensor/io/dark_frame_reader.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::filesystem::path path =
      std::filesystem::temp_directory_path() /
      ("camsim_fuzz_raw_dng_" + std::to_string(::getpid()) + ".dng");
  if (FILE* f = std::fopen(path.c_str(), "wb")) {
    const std::size_t written = size ? std::fwrite(data, 1, size, f) : 0;
    std::fclose(f);
    if (written != size) return 0;
  } else {
    return 0;
  }
  try {
    const camsim::RawImage raw = camsim::readRawDng(path);
    FUZZ_CHECK(raw.width > 0 && raw.height > 0);
    FUZZ_CHECK(raw.dn.size() ==
               static_cast<std::size_t>(raw.width) * static_cast<std::size_t>(raw.height));
    FUZZ_CHECK(raw.blackLevelDn >= 0.0 && raw.blackLevelDn <= 65535.0);
  } catch (const camsim::InputError&) {
  }
  return 0;
}
