// How long work reports how far it got. The library and the converters call it; only the program
// decides whether and how to show it (the `mosb` tool draws it on stderr when that is a terminal).
#pragma once

#include <cstdint>
#include <functional>
#include <string_view>

namespace mosb {

// Called with the name of the current stage, the units done so far and the units in that stage
// (0 when unknown). Calls come from one thread at a time; an empty Progress reports nothing.
using Progress =
    std::function<void(std::string_view stage, std::uint64_t done, std::uint64_t total)>;

inline void report(const Progress& progress, std::string_view stage, std::uint64_t done,
                   std::uint64_t total) {
  if (progress) progress(stage, done, total);
}

}  // namespace mosb
