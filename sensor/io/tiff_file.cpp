#include "sensor/io/tiff_file.h"

#include <tiffio.h>

#include <cstdarg>
#include <cstdio>

namespace camsim {
namespace {

// Keeps the first message. Declared printf-like so compilers check the forwarding of
// libtiff's format string.
__attribute__((format(printf, 4, 0))) int keepFirstError(TIFF*, void* userData, const char* module,
                                                         const char* fmt, va_list ap) {
  auto* message = static_cast<std::string*>(userData);
  if (message->empty()) {
    char buffer[512];
    std::vsnprintf(buffer, sizeof buffer, fmt, ap);
    *message = std::string(module ? module : "libtiff") + ": " + buffer;
  }
  return 1;
}

int ignoreWarning(TIFF*, void*, const char*, const char*, va_list) {
  return 1;
}

}  // namespace

void TiffCloser::operator()(TIFF* tif) const {
  TIFFClose(tif);
}

TiffPtr openTiff(const std::filesystem::path& path, const char* mode, std::string& error) {
  std::unique_ptr<TIFFOpenOptions, void (*)(TIFFOpenOptions*)> options(TIFFOpenOptionsAlloc(),
                                                                       &TIFFOpenOptionsFree);
  TIFFOpenOptionsSetErrorHandlerExtR(options.get(), &keepFirstError, &error);
  TIFFOpenOptionsSetWarningHandlerExtR(options.get(), &ignoreWarning, nullptr);
  return TiffPtr(TIFFOpenExt(path.c_str(), mode, options.get()));
}

}  // namespace camsim
