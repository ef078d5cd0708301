// The experiment file (spec/EXPERIMENT.md): TOML, read with toml++ into lib/experiment's plain
// Experiment. Every key is known, every value of its type; the limits parse. Problems are one
// mosb::Error line "FILE:LINE: KEY: problem", found before anything runs.
#pragma once

#include <filesystem>
#include <string_view>

#include "mosb/experiment.hpp"

namespace mosb::converters {

Experiment read_experiment_file(const std::filesystem::path& path);
// The same from text; `display_name` stands for the file in errors.
Experiment parse_experiment(std::string_view text, const std::string& display_name);

}  // namespace mosb::converters
