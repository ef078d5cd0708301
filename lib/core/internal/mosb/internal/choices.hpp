// The end of every "no such NAME" message: the names there are, and the one the user may have
// meant ("did you mean"), for commands, views, query sets and solvers alike.
#pragma once

#include <algorithm>
#include <string>
#include <string_view>
#include <vector>

namespace mosb {

// The edit distance of two words (insertions, deletions, substitutions). O(|a| |b|).
inline std::size_t edit_distance(std::string_view a, std::string_view b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t above = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = above;
    }
  }
  return row[b.size()];
}

// The choice within two edits of `given` and fewer than its length (the first of the nearest),
// or "" when none is: a one-letter name is no typo of another.
inline std::string nearest_choice(std::string_view given, const std::vector<std::string>& choices) {
  std::string best;
  std::size_t best_distance = std::min<std::size_t>(3, given.size());
  for (const auto& choice : choices)
    if (const auto d = edit_distance(given, choice); d < best_distance) {
      best = choice;
      best_distance = d;
    }
  return best;
}

// "(KIND: a, b, c)", "(KIND: a, b, c; did you mean 'b'?)" when one is within two edits of
// `given`, or "(KIND: none)".
inline std::string choices_text(std::string_view given, const std::vector<std::string>& choices,
                                std::string_view kind) {
  std::string text = "(" + std::string(kind) + ": ";
  if (choices.empty()) return text + "none)";
  for (std::size_t i = 0; i < choices.size(); ++i) text += (i > 0 ? ", " : "") + choices[i];
  if (const auto meant = nearest_choice(given, choices); !meant.empty())
    text += "; did you mean '" + meant + "'?";
  return text + ")";
}

}  // namespace mosb
