// One name table per named choice (white balance, demosaic, noise mode, sampler, …): the
// spellings a scene file, a front end's argument and the JSON sidecar share. Each enum's
// header holds its table next to the enum, as a specialisation of EnumNames:
//
//   template <> struct EnumNames<NoiseMode> {
//     static constexpr EnumName<NoiseMode> kTable[] = {{NoiseMode::kNone, "none"}, …};
//   };
//
// The first entry of a value is its canonical name, the one written (enumName); later
// entries of the same value are aliases, read (enumFromName) but neither written nor listed
// in messages (enumNameList), e.g. demosaic's "malvar-he-cutler" beside "malvar". Parsing,
// writing and messages all go through these functions, so the names cannot drift apart.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>

namespace camsim {

template <typename E>
struct EnumName {
  E value;
  std::string_view name;
};

// Specialised in each enum's header with `static constexpr EnumName<E> kTable[]`.
template <typename E>
struct EnumNames;

// The canonical name of `value` (its first entry); "" for a value without one.
template <typename E>
constexpr std::string_view enumName(E value) {
  for (const EnumName<E>& n : EnumNames<E>::kTable)
    if (n.value == value) return n.name;
  return {};
}

// The value `name` spells (a canonical name or an alias); nullopt if none.
template <typename E>
constexpr std::optional<E> enumFromName(std::string_view name) {
  for (const EnumName<E>& n : EnumNames<E>::kTable)
    if (n.name == name) return n.value;
  return std::nullopt;
}

// Whether entry i of the table is the first of its value (a canonical name, not an alias).
template <typename E>
constexpr bool isCanonicalEntry(std::size_t i) {
  for (std::size_t k = 0; k < i; ++k)
    if (EnumNames<E>::kTable[k].value == EnumNames<E>::kTable[i].value) return false;
  return true;
}

// The canonical names in table order, comma-separated ("none, photon, full"): for messages
// and help text.
template <typename E>
std::string enumNameList() {
  std::string list;
  std::size_t i = 0;
  for (const EnumName<E>& n : EnumNames<E>::kTable) {
    if (isCanonicalEntry<E>(i++)) list += (list.empty() ? "" : ", ") + std::string(n.name);
  }
  return list;
}

}  // namespace camsim
