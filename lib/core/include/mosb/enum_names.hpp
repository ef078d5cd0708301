// The names of an enum's values, one table per enum: what to_string prints, what a parser
// accepts, what a command line offers and what a JSON report keys by all read the same table, so
// they cannot disagree. Names are the spec's spelling (lower case, words joined by '-' or '_' as
// the spec has them).
#pragma once

#include <array>
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace mosb {

template <class Enum>
struct EnumName {
  Enum value;
  std::string_view name;
};

template <class Enum, std::size_t N>
struct EnumNames {
  std::array<EnumName<Enum>, N> entries;

  // The value's name. Precondition: `value` is in the table; a value outside it (a programming
  // error, or a byte no reader checked) is "?", never undefined behaviour.
  constexpr std::string_view name(Enum value) const {
    for (const auto& entry : entries)
      if (entry.value == value) return entry.name;
    return "?";
  }
  // The value named exactly `text`, or nullopt.
  constexpr std::optional<Enum> parse(std::string_view text) const {
    for (const auto& entry : entries)
      if (entry.name == text) return entry.value;
    return std::nullopt;
  }
  // Every name in table order (a command line's choices).
  std::vector<std::string> names() const {
    std::vector<std::string> out;
    out.reserve(N);
    for (const auto& entry : entries) out.emplace_back(entry.name);
    return out;
  }
  // "a, b, c": the names for a message.
  std::string choices_text() const {
    std::string out;
    for (std::size_t i = 0; i < N; ++i)
      out += std::string(i == 0 ? "" : ", ") + std::string(entries[i].name);
    return out;
  }
};

// The table of a braced list: `enum_names<Color>({{Color::red, "red"}, {Color::blue, "blue"}})`.
template <class Enum, std::size_t N>
constexpr EnumNames<Enum, N> enum_names(const EnumName<Enum> (&list)[N]) {
  EnumNames<Enum, N> table{};
  for (std::size_t i = 0; i < N; ++i) table.entries[i] = list[i];
  return table;
}

}  // namespace mosb
