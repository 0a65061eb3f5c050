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

namespace {

// The used slots ranked by count, ties by entry (an insertion sort; entries are distinct, so
// the order is total and any correct sort gives it); unused slots (count 0) stay at the end.
IdFilm::Slots ranked(const IdFilm::Slots& slots) {
  IdFilm::Slots s{};
  int used = 0;
  for (const IdFilm::Slot& slot : slots) {
    if (slot.count == 0) break;  // slots fill in order
    int i = used++;
    for (; i > 0; --i) {
      const IdFilm::Slot& prev = s[static_cast<std::size_t>(i - 1)];
      if (prev.count > slot.count || (prev.count == slot.count && prev.entry < slot.entry)) break;
      s[static_cast<std::size_t>(i)] = prev;
    }
    s[static_cast<std::size_t>(i)] = slot;
  }
  return s;
}

}  // namespace

void IdFilm::write(const Slots& slots, int samplesPerPixel, float* out) const {
  // Most pixels see one id: their slots are already in rank order.
  const Slots s = slots[1].count == 0 ? slots : ranked(slots);
  for (int c = 0; c < 2 * kRanks + 1; ++c) out[c] = 0.0f;
  for (int r = 0; r < kRanks && s[static_cast<std::size_t>(r)].count > 0; ++r) {
    const Slot& slot = s[static_cast<std::size_t>(r)];
    out[2 * r] = ids_[slot.entry];
    out[2 * r + 1] = static_cast<float>(static_cast<double>(slot.count) / samplesPerPixel);
  }
  if (s[0].count > 0) out[2 * kRanks] = static_cast<float>(numbers_[s[0].entry]);
}

}  // namespace camsim
