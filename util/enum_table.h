// The names of an enum's values, in one table: what a configuration key, a record field or a
// command-line choice reads and writes. Every enum a file names is read through one of these.
//
//   inline constexpr EnumTable<TrackerMode, 2> kTrackerModes = {{{
//       {TrackerMode::kThesis, "thesis"}, {TrackerMode::kBounded, "bounded"}}}};
//   kTrackerModes.Name(TrackerMode::kBounded)         // "bounded"
//   kTrackerModes.FromName("thesis", &mode)           // true, mode = kThesis
//   kTrackerModes.Names()                             // {"thesis", "bounded"}, table order
#pragma once

#include <array>
#include <cstddef>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace attend {

template <typename Enum, std::size_t N>
struct EnumTable {
  std::array<std::pair<Enum, const char*>, N> entries;

  // The value's name; "?" for a value the table does not hold.
  constexpr const char* Name(Enum value) const {
    for (const auto& [entry, name] : entries) {
      if (entry == value) return name;
    }
    return "?";
  }
  // The value called `name`; false (and `value` unchanged) when there is none.
  bool FromName(std::string_view name, Enum* value) const {
    for (const auto& [entry, entry_name] : entries) {
      if (name == entry_name) {
        *value = entry;
        return true;
      }
    }
    return false;
  }
  // Every name, in the table's order.
  std::vector<std::string> Names() const {
    std::vector<std::string> names;
    names.reserve(N);
    for (const auto& entry : entries) names.emplace_back(entry.second);
    return names;
  }
};

}  // namespace attend
