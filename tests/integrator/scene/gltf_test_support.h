// Builds small glTF 2.0 files for tests: accessor data goes into one buffer embedded as a
// base64 data URI; the test writes the rest of the JSON (nodes, meshes, animations, …).
//   GltfBuilder b;
//   const int pos = b.floats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3");
//   const std::string text = b.json(R"("meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
//                                      "nodes": [{"mesh": 0}], "scenes": [{"nodes": [0]}])");
#pragma once

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace camsim::test {

// The glTF files of tests/data/gltf.
inline const std::filesystem::path kGltfData = std::filesystem::path(CAMSIM_TEST_DATA_DIR) / "gltf";

class GltfBuilder {
 public:
  // An accessor of FLOAT components ("SCALAR", "VEC2", "VEC3", "VEC4"); returns its index.
  int floats(const std::vector<float>& v, const std::string& type) {
    const size_t comps = type == "SCALAR" ? 1 : static_cast<size_t>(type.back() - '0');
    std::string bytes(v.size() * 4, '\0');
    std::memcpy(bytes.data(), v.data(), bytes.size());
    return add(bytes, 5126, v.size() / comps, type);
  }
  // An accessor of UNSIGNED_SHORT scalars (indices).
  int u16(const std::vector<std::uint16_t>& v) {
    std::string bytes(v.size() * 2, '\0');
    std::memcpy(bytes.data(), v.data(), bytes.size());
    return add(bytes, 5123, v.size(), "SCALAR");
  }
  // An accessor of UNSIGNED_BYTE components (colours: normalized).
  int u8(const std::vector<std::uint8_t>& v, const std::string& type, bool normalized) {
    const size_t comps = type == "SCALAR" ? 1 : static_cast<size_t>(type.back() - '0');
    return add(std::string(v.begin(), v.end()), 5121, v.size() / comps, type, normalized);
  }
  // The file: the accessors, views and buffer written here, then `rest` (JSON members).
  std::string json(const std::string& rest) const {
    std::string views, accessors;
    for (size_t i = 0; i < views_.size(); ++i)
      views += (i ? "," : "") + std::string("{\"buffer\":0,\"byteOffset\":") +
               std::to_string(views_[i].first) +
               ",\"byteLength\":" + std::to_string(views_[i].second) + "}";
    for (size_t i = 0; i < accessors_.size(); ++i) accessors += (i ? "," : "") + accessors_[i];
    std::string out = "{\"asset\":{\"version\":\"2.0\"}";
    if (!data_.empty())
      out += ",\"buffers\":[{\"byteLength\":" + std::to_string(data_.size()) +
             ",\"uri\":\"data:application/octet-stream;base64," + base64(data_) + "\"}]" +
             ",\"bufferViews\":[" + views + "],\"accessors\":[" + accessors + "]";
    return out + (rest.empty() ? "" : "," + rest) + "}";
  }

  static std::string base64(const std::string& in) {
    static const char* table = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    for (size_t i = 0; i < in.size(); i += 3) {
      std::uint32_t n = static_cast<std::uint32_t>(static_cast<unsigned char>(in[i])) << 16;
      if (i + 1 < in.size())
        n |= static_cast<std::uint32_t>(static_cast<unsigned char>(in[i + 1])) << 8;
      if (i + 2 < in.size()) n |= static_cast<unsigned char>(in[i + 2]);
      out += table[(n >> 18) & 63];
      out += table[(n >> 12) & 63];
      out += i + 1 < in.size() ? table[(n >> 6) & 63] : '=';
      out += i + 2 < in.size() ? table[n & 63] : '=';
    }
    return out;
  }

 private:
  int add(const std::string& bytes, int componentType, size_t count, const std::string& type,
          bool normalized = false) {
    while (data_.size() % 4) data_ += '\0';
    views_.emplace_back(data_.size(), bytes.size());
    data_ += bytes;
    accessors_.push_back("{\"bufferView\":" + std::to_string(views_.size() - 1) +
                         ",\"componentType\":" + std::to_string(componentType) +
                         ",\"count\":" + std::to_string(count) + ",\"type\":\"" + type + "\"" +
                         (normalized ? ",\"normalized\":true}" : "}"));
    return static_cast<int>(accessors_.size()) - 1;
  }

  std::string data_;
  std::vector<std::pair<size_t, size_t>> views_;
  std::vector<std::string> accessors_;
};

inline void writeText(const std::filesystem::path& file, const std::string& text) {
  std::ofstream(file, std::ios::binary) << text;
}

}  // namespace camsim::test
