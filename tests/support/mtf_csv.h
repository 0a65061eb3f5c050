// Test support: reading what `camsim mtf` writes — mtf.csv as columns of numbers, and one
// channel's number from mtf.json (sensor/measure/mtf_measurement.h's layout: a "channels"
// list of objects, each opening with "name").
#pragma once

#include <cstdlib>
#include <filesystem>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "tests/support/text_file.h"

namespace camsim::test {

struct MtfCsv {
  std::vector<std::string> columns;
  std::vector<std::vector<double>> rows;
};

inline MtfCsv readMtfCsv(const std::filesystem::path& path) {
  MtfCsv csv;
  std::istringstream in(readFile(path));
  std::string line;
  if (std::getline(in, line)) {
    std::istringstream header(line);
    for (std::string c; std::getline(header, c, ',');) csv.columns.push_back(c);
  }
  while (std::getline(in, line)) {
    std::vector<double> row;
    std::istringstream cells(line);
    for (std::string c; std::getline(cells, c, ',');)
      row.push_back(std::strtod(c.c_str(), nullptr));
    csv.rows.push_back(row);
  }
  return csv;
}

// The number after "key": in the channel object named `channel`; NaN if absent.
inline double jsonChannelNumber(const std::string& json, const std::string& channel,
                                const std::string& key) {
  const size_t at = json.find("\"name\": \"" + channel + "\"");
  if (at == std::string::npos) return std::numeric_limits<double>::quiet_NaN();
  const size_t end = json.find('}', at);
  const size_t k = json.find("\"" + key + "\": ", at);
  if (k == std::string::npos || k > end) return std::numeric_limits<double>::quiet_NaN();
  return std::strtod(json.c_str() + k + key.size() + 4, nullptr);
}

}  // namespace camsim::test
