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
//
// The counts of one pixel live in its renderer's scratch (Slots, in AovPixelState of
// aov_film.h), not in a film-sized array: the render loop counts a pixel's samples there and writes the finished
// channels once (write).
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "integrator/scene/scene_ids.h"

namespace camsim {

class IdFilm {
 public:
  static constexpr int kSlots = 8;
  static constexpr int kRanks = 6;
  static_assert(kRanks % 2 == 0 && kRanks <= 20, "two ranks per layer, layers 00 … 09");
  static_assert(kRanks <= kSlots, "every rank has a slot");

  // One pixel's distinct ids in order of first appearance, with their sample counts.
  struct Slot {
    std::uint32_t entry = 0, count = 0;
  };
  using Slots = std::array<Slot, kSlots>;

  IdFilm(IdKind kind, const IdTable& table);

  // One sample of the pixel whose slots these are, on table entry `entry`. Returns the
  // entry's slot (a further sample of the same entry may add to it directly), or none when
  // the pixel's slots are full of other ids.
  static Slot* add(Slots& slots, std::uint32_t entry) {
    for (Slot& s : slots) {
      if (s.count == 0) s.entry = entry;
      if (s.entry == entry) {
        ++s.count;
        return &s;
      }
    }
    return nullptr;
  }
  // The channel names (kRanks · 2 + 1), in the table's order.
  const std::vector<std::string>& channels() const { return channels_; }
  // Writes a pixel's channels (channels().size() floats) at out from its slots.
  void write(const Slots& slots, int samplesPerPixel, float* out) const;

 private:
  std::vector<std::string> channels_;
  std::vector<float> ids_;              // per entry: cryptomatteId(name)
  std::vector<std::uint32_t> numbers_;  // per entry: the dominant-id number
};

}  // namespace camsim
