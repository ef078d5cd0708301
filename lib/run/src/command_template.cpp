#include "mosb/command_template.hpp"

#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cstdlib>
#include <cstring>
#include <sstream>

#include "mosb/error.hpp"

namespace mosb {

namespace {

[[noreturn]] void refuse(const std::string& message) {
  throw Error(ErrorCode::invalid_argument, {setting("solver_template"), ": " + message});
}

bool is_blank(char c) {
  return c == ' ' || c == '\t' || c == '\n';
}

// Inside "...": a backslash escapes only these (POSIX 2.2.3); before anything else it is literal.
bool escapable_in_double_quotes(char c) {
  return c == '"' || c == '\\' || c == '$' || c == '`';
}

// Appends the double-quoted text starting after the opening quote at `i`; returns the index of
// the closing quote.
std::size_t double_quoted(std::string_view text, std::size_t i, std::string& word) {
  for (++i; i < text.size() && text[i] != '"'; ++i) {
    if (text[i] == '\\' && i + 1 < text.size()) {
      if (text[i + 1] == '\n') {
        ++i;
        continue;
      }
      if (escapable_in_double_quotes(text[i + 1])) ++i;
    }
    word += text[i];
  }
  if (i >= text.size()) refuse("unterminated double quote");
  return i;
}

}  // namespace

std::string shell_quote(const std::string& word) {
  const bool safe = !word.empty() && std::all_of(word.begin(), word.end(), [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || std::strchr("_-./=:,+@%", c);
  });
  if (safe) return word;
  std::string quoted = "'";
  for (const char c : word) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return quoted + "'";
}

std::vector<std::string> split_command(std::string_view text) {
  std::vector<std::string> words;
  std::string word;
  bool in_word = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (is_blank(c)) {
      if (in_word) words.push_back(std::move(word));
      word.clear();
      in_word = false;
      continue;
    }
    if (c == '\\') {
      if (i + 1 >= text.size()) refuse("a backslash ends the command");
      ++i;
      if (text[i] == '\n') continue;  // line continuation
      word += text[i];
    } else if (c == '\'') {
      const std::size_t close = text.find('\'', i + 1);
      if (close == std::string_view::npos) refuse("unterminated single quote");
      word.append(text.substr(i + 1, close - i - 1));
      i = close;
    } else if (c == '"') {
      i = double_quoted(text, i, word);
    } else {
      word += c;
    }
    in_word = true;
  }
  if (in_word) words.push_back(std::move(word));
  if (words.empty()) refuse("the command is empty");
  return words;
}

std::span<const std::string_view> run_placeholders() {
  static constexpr std::array<std::string_view, 9> names = {
      "instance", "view", "objectives", "query", "source", "target", "front", "fronts", "threads"};
  return names;
}

namespace {

// Calls `literal(text)` and `placeholder(name)` for the pieces of `word`, left to right.
template <class Literal, class Placeholder>
void scan_word(const std::string& word, Literal literal, Placeholder placeholder) {
  for (std::size_t i = 0; i < word.size(); ++i) {
    const char c = word[i];
    if ((c == '{' || c == '}') && i + 1 < word.size() && word[i + 1] == c) {
      literal(std::string_view(&word[i], 1));
      ++i;
    } else if (c == '{') {
      const std::size_t close = word.find('}', i + 1);
      if (close == std::string::npos)
        refuse("'{' without '}' in '" + word + "' (write {{ for a literal brace)");
      placeholder(std::string_view(word).substr(i + 1, close - i - 1));
      i = close;
    } else if (c == '}') {
      refuse("'}' without '{' in '" + word + "' (write }} for a literal brace)");
    } else {
      literal(std::string_view(&word[i], 1));
    }
  }
}

std::string known_list(std::span<const std::string_view> known) {
  std::string list;
  for (const auto name : known) list += (list.empty() ? "{" : ", {") + std::string(name) + "}";
  return list;
}

}  // namespace

std::vector<std::string> template_placeholders(std::span<const std::string> words,
                                               std::span<const std::string_view> known) {
  std::vector<std::string> used;
  for (const auto& word : words)
    scan_word(
        word, [](std::string_view) {},
        [&](std::string_view name) {
          if (std::find(known.begin(), known.end(), name) == known.end())
            refuse("unknown placeholder {" + std::string(name) + "} (known: " + known_list(known) +
                   ")");
          if (std::find(used.begin(), used.end(), name) == used.end()) used.emplace_back(name);
        });
  return used;
}

std::vector<std::string> expand_command(std::span<const std::string> words,
                                        const std::map<std::string, std::string>& values) {
  std::vector<std::string> out;
  out.reserve(words.size());
  for (const auto& word : words) {
    std::string expanded;
    scan_word(
        word, [&](std::string_view text) { expanded += text; },
        [&](std::string_view name) {
          const auto it = values.find(std::string(name));
          if (it == values.end()) refuse("unknown placeholder {" + std::string(name) + "}");
          expanded += it->second;
        });
    out.push_back(std::move(expanded));
  }
  return out;
}

std::string resolve_executable(const std::string& name) {
  if (name.find('/') != std::string::npos) return name;
  const char* path = std::getenv("PATH");
  std::stringstream dirs(path ? path : "/usr/local/bin:/usr/bin:/bin");
  for (std::string dir; std::getline(dirs, dir, ':');) {
    std::string candidate = (dir.empty() ? "." : dir) + "/" + name;
    struct stat st {};
    if (::stat(candidate.c_str(), &st) == 0 && S_ISREG(st.st_mode) &&
        ::access(candidate.c_str(), X_OK) == 0)
      return candidate;
  }
  return {};
}

std::string template_executable(std::string_view solver_template) {
  const auto words = split_command(solver_template);
  template_placeholders(words, run_placeholders());
  if (!template_placeholders(std::span(words.data(), 1), run_placeholders()).empty())
    throw Error(ErrorCode::invalid_argument,
                "the program '" + words.front() +
                    "' is a placeholder: the template starts with the solver's executable");
  auto executable = resolve_executable(words.front());
  if (executable.empty())
    throw Error(ErrorCode::invalid_argument,
                words.front() + ": no such executable" +
                    (words.front().find('/') == std::string::npos ? " in PATH" : ""));
  if (::access(executable.c_str(), X_OK) != 0)
    throw Error(ErrorCode::invalid_argument, executable + ": not an executable file");
  return executable;
}

}  // namespace mosb
