#include "integrator/render/id_film.h"

#include "integrator/render/cryptomatte.h"

namespace camsim {

IdFilm::IdFilm(IdKind kind, const IdTable& table) : numbers_(table.numbers) {
  const std::string type = cryptomatteTypeName(kind);
  for (int layer = 0; layer < kRanks / 2; ++layer) {
    const std::string suffix = "0" + std::to_string(layer);  // 00, 01, 02 (kRanks ≤ 20)
    for (const char* c : {".R", ".G", ".B", ".A"}) channels_.push_back(type + suffix + c);
  }
  channels_.push_back(std::string(idKindName(kind)) + ".id");
  for (const std::string& name : table.names) ids_.push_back(cryptomatteId(name));
}

void IdFilm::write(const Slots& slots, int samplesPerPixel, float* out) const {
  // Rank by count, ties by entry: an insertion sort of the used slots (entries are
  // distinct, so the order is total and any correct sort gives it).
  Slots s{};
  int used = 0;
  for (const Slot& slot : slots) {
    if (slot.count == 0) break;  // slots fill in order
    int i = used++;
    for (; i > 0; --i) {
      const Slot& prev = s[static_cast<std::size_t>(i - 1)];
      if (prev.count > slot.count || (prev.count == slot.count && prev.entry < slot.entry)) break;
      s[static_cast<std::size_t>(i)] = prev;
    }
    s[static_cast<std::size_t>(i)] = slot;
  }
  for (int r = 0; r < kRanks; ++r) {
    const Slot& slot = s[static_cast<std::size_t>(r)];
    out[2 * r] = r < used ? ids_[slot.entry] : 0.0f;
    out[2 * r + 1] =
        r < used ? static_cast<float>(static_cast<double>(slot.count) / samplesPerPixel) : 0.0f;
  }
  out[2 * kRanks] = used > 0 ? static_cast<float>(numbers_[s[0].entry]) : 0.0f;
}

}  // namespace camsim
