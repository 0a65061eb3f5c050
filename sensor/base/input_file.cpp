// Reading a user-named input file (input_file.h).
#include "sensor/base/input_file.h"

#include <cstdio>
#include <memory>
#include <system_error>

#include "sensor/base/format.h"
#include "sensor/base/input_error.h"

namespace camsim {

std::string readInputFile(const std::filesystem::path& path, const std::string& what,
                          std::uintmax_t maxBytes) {
  const std::string name = path.string();
  std::error_code ec;
  const std::filesystem::file_status status = std::filesystem::status(path, ec);
  if (ec || !std::filesystem::exists(status))
    throw InputError({name, 0, 0}, "", "cannot open " + what + ": no such file");
  if (std::filesystem::is_directory(status))
    throw InputError({name, 0, 0}, "", "cannot open " + what + ": it is a directory");
  if (!std::filesystem::is_regular_file(status) && !std::filesystem::is_fifo(status))
    throw InputError({name, 0, 0}, "",
                     "cannot read " + what + ": not a regular file or a pipe (a device?)");
  const auto tooLarge = [&] {
    return InputError({name, 0, 0}, "",
                      what + " is larger than " + formatNumber(static_cast<double>(maxBytes)) +
                          " bytes (limit kMaxInputFileBytes)");
  };
  if (std::filesystem::is_regular_file(status)) {  // a pipe's size is known only at its end
    const std::uintmax_t size = std::filesystem::file_size(path, ec);
    if (!ec && size > maxBytes) throw tooLarge();
  }
  const auto closer = [](std::FILE* f) { std::fclose(f); };
  const std::unique_ptr<std::FILE, decltype(closer)> file(std::fopen(name.c_str(), "rb"), closer);
  if (!file) throw InputError({name, 0, 0}, "", "cannot open " + what);
  std::string bytes;
  char buffer[1 << 16];
  while (true) {
    const std::size_t got = std::fread(buffer, 1, sizeof buffer, file.get());
    if (got > 0) {
      if (bytes.size() + got > maxBytes) throw tooLarge();
      bytes.append(buffer, got);
    }
    if (got < sizeof buffer) break;
  }
  if (std::ferror(file.get())) throw InputError({name, 0, 0}, "", "cannot read " + what);
  return bytes;
}

}  // namespace camsim
