// Solver command templates of `mosb run` (spec/RUN.md §2): a command line split into words as a
// POSIX shell splits a simple command (quotes and backslashes, no expansion of any kind), whose
// words hold placeholders `{name}` filled per query. The words are executed without a shell, so
// a file name with a blank, a quote or a `;` stays one argument.
#pragma once

#include <map>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace mosb {

// The words of `text`: blanks (space, tab, newline) separate words; '...' keeps everything
// literally; "..." keeps everything but \" \\ \$ \` and backslash-newline; outside quotes a
// backslash takes the next character literally (backslash-newline disappears). `$`, `*`, `;`,
// `|`, `>` and the like are ordinary characters. Throws mosb::Error (invalid_argument) on an
// unterminated quote, a trailing backslash or no word at all.
std::vector<std::string> split_command(std::string_view text);

// A word quoted for sh, which split_command reads back as exactly `word`: as it is when it is made
// of safe characters only ([A-Za-z0-9_./=:,+@%-]), else in single quotes.
std::string shell_quote(const std::string& word);

// The placeholders `mosb run` fills: instance, view, objectives, query, source, target, front,
// fronts, threads.
std::span<const std::string_view> run_placeholders();

// The placeholder names used in `words` (`{name}`; `{{` and `}}` stand for literal braces), in
// order of first use. Throws mosb::Error (invalid_argument) "--solver: unknown placeholder {x}
// (known: ...)" for a name outside `known`, and on a lone `{` or `}`.
std::vector<std::string> template_placeholders(std::span<const std::string> words,
                                               std::span<const std::string_view> known);

// `words` with every placeholder replaced by its value in `values` (each word stays one argument,
// whatever its value holds). A placeholder without a value is an error, as above.
std::vector<std::string> expand_command(std::span<const std::string> words,
                                        const std::map<std::string, std::string>& values);

// The executable `name` (a template's first word) names: a name with '/' as it is, else the first
// executable file of that name in $PATH (empty when none).
std::string resolve_executable(const std::string& name);

// The program `solver_template` runs: its first word, which must not be a placeholder, resolved
// (resolve_executable) to an executable file; every placeholder must be one of
// run_placeholders(). Throws mosb::Error (invalid_argument) naming what is wrong. The one check
// of a template, for `mosb run`, its SLURM tasks and experiments alike.
std::string template_executable(std::string_view solver_template);

}  // namespace mosb
