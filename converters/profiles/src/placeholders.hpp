// The placeholders of a profile's command words (`{name}`, with `{{` and `}}` for literal braces),
// read and filled in one place for the parser and the run.
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace mosb::converters::profile_internal {

// The names in `word`, in order; nullopt when a brace is alone (a `{` without its `}`, a `}`).
std::optional<std::vector<std::string>> placeholder_names(std::string_view word);

using PlaceholderValue = std::function<std::optional<std::string>(const std::string&)>;

// `word` with each placeholder `fill` knows (it returns a value) replaced by that value, whose
// braces are doubled so that a later expansion keeps them literal; the others, and `{{` `}}`,
// kept as they are: a template filled in part.
std::string fill_placeholders(std::string_view word, const PlaceholderValue& fill);

// `word` with every placeholder replaced by its value as it is and `{{` `}}` by one brace; throws
// mosb::Error (naming `what`) for a placeholder `fill` does not know or a lone brace.
std::string expand_placeholders(std::string_view word, const PlaceholderValue& fill,
                                const std::string& what);

}  // namespace mosb::converters::profile_internal
