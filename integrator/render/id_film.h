// IdFilm: one kind of ID matte (instance, class or material; scene_ids.h) as Cryptomatte's
// ranking pixel filter computes it. Every camera sample of a pixel adds one count to the id
// its first hit has (a miss, or a shape without one, adds to id 0, "nothing"); with the box
// filter over the photosite all weights are equal, so an id's coverage is its count over
// the samples per pixel and the coverages of a pixel sum to 1. Ids never average.
//
// | channels                        | meaning |
// |---------------------------------|---------|
// | T00.R, T00.G, T00.B, T00.A      | id rank 0, its coverage, id rank 1, its coverage |
// | T01.*, T02.*                    | ranks 2–3 and 4–5 (6 ranks: Cryptomatte's default) |
// | KIND.id                         | the dominant id's number (scene_ids.h), an exact integer as float |
//
// T is the type name (CryptoObject, CryptoClass, CryptoMaterial); ids are
// cryptomatteId(name), ranks by coverage, ties by entry. A pixel keeps its first
// kSlots distinct ids; the samples of a further id (more than 8 objects in one pixel) are
// not counted, so its coverages then sum to less than 1.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <glm/vec2.hpp>

#include "integrator/scene/scene_ids.h"

namespace camsim {

class IdFilm {
 public:
  static constexpr int kSlots = 8;
  static constexpr int kRanks = 6;
  static_assert(kRanks % 2 == 0 && kRanks <= 20, "two ranks per layer, layers 00 … 09");

  IdFilm(glm::ivec2 resolution, IdKind kind, const IdTable& table);

  void add(glm::ivec2 pixel, std::uint32_t entry) {
    Slot* s = &slots_[(static_cast<std::size_t>(pixel.y) * static_cast<std::size_t>(resolution_.x) +
                       static_cast<std::size_t>(pixel.x)) *
                      kSlots];
    for (int i = 0; i < kSlots; ++i, ++s) {
      if (s->count == 0) s->entry = entry;
      if (s->entry == entry) {
        ++s->count;
        return;
      }
    }
  }
  // The channel names (kRanks · 2 + 1), in the table's order.
  const std::vector<std::string>& channels() const { return channels_; }
  // Writes pixel px's channels (channels().size() floats) at out.
  void pixel(std::size_t px, int samplesPerPixel, float* out) const;

 private:
  struct Slot {
    std::uint32_t entry = 0, count = 0;
  };
  glm::ivec2 resolution_;
  std::vector<std::string> channels_;
  std::vector<float> ids_;              // per entry: cryptomatteId(name)
  std::vector<std::uint32_t> numbers_;  // per entry: the dominant-id number
  std::vector<Slot> slots_;
};

}  // namespace camsim
