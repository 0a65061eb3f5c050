#include "integrator/render/id_film.h"

#include <algorithm>
#include <array>

#include "integrator/render/cryptomatte.h"

namespace camsim {

IdFilm::IdFilm(glm::ivec2 resolution, IdKind kind, const IdTable& table)
    : resolution_(resolution), numbers_(table.numbers) {
  const std::string type = cryptomatteTypeName(kind);
  for (int layer = 0; layer < kRanks / 2; ++layer) {
    const std::string suffix = "0" + std::to_string(layer);  // 00, 01, 02 (kRanks ≤ 20)
    for (const char* c : {".R", ".G", ".B", ".A"}) channels_.push_back(type + suffix + c);
  }
  channels_.push_back(std::string(idKindName(kind)) + ".id");
  for (const std::string& name : table.names) ids_.push_back(cryptomatteId(name));
  slots_.resize(static_cast<std::size_t>(resolution.x) * static_cast<std::size_t>(resolution.y) *
                kSlots);
}

void IdFilm::pixel(std::size_t px, int samplesPerPixel, float* out) const {
  std::array<Slot, kSlots> s;
  std::copy_n(&slots_[px * kSlots], kSlots, s.begin());
  std::stable_sort(s.begin(), s.end(), [](const Slot& a, const Slot& b) {
    return a.count != b.count ? a.count > b.count : a.entry < b.entry;
  });
  for (int r = 0; r < kRanks; ++r) {
    const bool used = s[static_cast<std::size_t>(r)].count > 0;
    out[2 * r] = used ? ids_[s[static_cast<std::size_t>(r)].entry] : 0.0f;
    out[2 * r + 1] =
        used ? static_cast<float>(static_cast<double>(s[static_cast<std::size_t>(r)].count) /
                                  samplesPerPixel)
             : 0.0f;
  }
  out[2 * kRanks] = s[0].count > 0 ? static_cast<float>(numbers_[s[0].entry]) : 0.0f;
}

}  // namespace camsim
