// libFuzzer target: arbitrary bytes through the experiment file's parser (converters/experiment,
// TOML via toml++). Any outcome but a clean mosb::Error of one line naming the file, or an
// Experiment that keeps the parser's promises (a name, a solver, exactly one of store and
// instances, exactly one of template and profile per solver), is a bug.
#include <cstdint>
#include <string>
#include <string_view>

#include "mosb/converters/experiment_file.hpp"
#include "mosb/error.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  static const std::string name = "fuzz.toml";
  try {
    const auto e = mosb::converters::parse_experiment(text, name);
    if (e.name.empty() || e.solvers.empty() || e.store.empty() == e.instances.empty())
      __builtin_trap();
    if (e.benchmarks.size() != e.benchmark_sources.size()) __builtin_trap();
    for (const auto& s : e.solvers) {
      if (s.name.empty() || s.spec.solver_template.empty() == s.spec.profile.empty())
        __builtin_trap();
      if (s.benchmarks.size() != s.benchmark_sources.size()) __builtin_trap();
    }
  } catch (const mosb::Error& error) {
    const std::string_view message = error.what();
    if (!message.starts_with(name + ":") || message.find('\n') != std::string_view::npos)
      __builtin_trap();
  }
  return 0;
}
