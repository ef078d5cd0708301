// Full verification: every checksum and every structural rule of spec/FORMAT.md §9, over the whole
// file. Separate from opening, which stays O(1) in the file size.
#pragma once

#include <optional>
#include <string>
#include <string_view>

#include "mosb/graph_reader.hpp"
#include "mosb/progress.hpp"

namespace mosb {

// VerifyLevel is declared in graph_reader.hpp (GraphReader::open takes one).

std::optional<VerifyLevel> parse_verify_level(std::string_view text);  // kVerifyLevelNames

// The first problem found, as "section 'NAME': [rule] detail"; nullopt when the file passes.
// `progress` hears stage "verify" as the checks finish (from one thread at a time).
std::optional<std::string> verify(const GraphReader& reader, VerifyLevel level,
                                  const Progress& progress = {});

// §1 padding: the first byte of [128, table_offset) outside every section's stored bytes that is
// not zero, as "[padding] byte B (before section 'S') is 0x.."; nullopt when there is none. Part
// of verify()'s structure level; public for packed files, whose stored bytes are their frames
// (their padding is checked on the packed bytes themselves, before they are decoded).
std::optional<std::string> find_padding_problem(const ContainerReader& reader);
// The same over the bytes of a container of any kind and what parse_container found in them.
std::optional<std::string> find_padding_problem(std::span<const std::byte> bytes,
                                                const Container& container);

}  // namespace mosb
