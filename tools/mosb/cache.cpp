// `mosb cache clear`: removes the text forms solver profiles had exported (spec/RUN.md §10.3);
// the cache itself is converters/profiles' export_cache.hpp.
#include <CLI/CLI.hpp>
#include <iostream>
#include <memory>

#include "commands.hpp"
#include "json_writer.hpp"
#include "mosb/converters/export_cache.hpp"
#include "mosb/internal/utf8.hpp"

namespace mosb::cli {

namespace {

struct CacheArgs {
  std::string directory;
  bool json = false;
};

int run_cache_clear(const CacheArgs& a) {
  const auto directory =
      a.directory.empty() ? converters::default_export_cache() : std::filesystem::path(a.directory);
  const auto [removed, left] = converters::clear_export_cache(directory);
  for (const auto& line : left) std::cerr << "mosb: " << escape_for_terminal(line) << "\n";
  if (a.json) {
    JsonWriter json(std::cout);
    json.begin_object();
    json.key("directory").value(directory.string());
    json.key("removed").value(removed);
    json.key("left").begin_array();
    for (const auto& line : left) json.value(line);
    json.end_array();
    json.end_object();
  } else {
    std::cout << "removed " << removed << " export" << (removed == 1 ? "" : "s") << " from "
              << escape_for_terminal(directory.string()) << "\n";
  }
  return 0;
}

Command add_cache_clear(CLI::App& parent) {
  auto* clear = parent.add_subcommand(
      "clear",
      "remove the text exports solver profiles made (made again when needed) and temporaries of "
      "killed runs; anything else in the directory is left alone and named on stderr");
  auto args = std::make_shared<CacheArgs>();
  clear
      ->add_option("--export-cache", args->directory,
                   "the cache (default $MOSB_EXPORT_CACHE, else $XDG_CACHE_HOME/mosb/exports, "
                   "else ~/.cache/mosb/exports)")
      ->option_text("DIR");
  add_json_flag(clear, args->json);
  return {clear, [args] { return run_cache_clear(*args); }};
}

}  // namespace

Command add_cache(CLI::App& app) {
  auto* cache = app.add_subcommand("cache", "The export cache of mosb run --profile");
  return group(cache, {add_cache_clear(*cache)});
}

}  // namespace mosb::cli
