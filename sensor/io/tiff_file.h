// Opening TIFF/DNG files through libtiff with camsim's handlers: the first error message
// is kept (for the exception the caller throws), warnings are dropped. Shared by the DNG
// writer and the dark-frame reader; this header does not include libtiff.
#pragma once

#include <filesystem>
#include <memory>
#include <string>

typedef struct tiff TIFF;  // libtiff's handle (tiffio.h declares it the same way)

namespace camsim {

// PhotometricInterpretation LinearRaw (DNG); libtiff's tiff.h does not name it.
inline constexpr int kPhotometricLinearRaw = 34892;

struct TiffCloser {
  void operator()(TIFF* tif) const;
};
using TiffPtr = std::unique_ptr<TIFF, TiffCloser>;

// mode "r" or "w". Null on failure. libtiff writes its first error message of this file
// into `error`, now and later: `error` must outlive the handle.
TiffPtr openTiff(const std::filesystem::path& path, const char* mode, std::string& error);

}  // namespace camsim
