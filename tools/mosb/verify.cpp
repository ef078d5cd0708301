#include "mosb/verify.hpp"

#include <CLI/CLI.hpp>
#include <iostream>
#include <memory>

#include "commands.hpp"

namespace mosb::cli {

Command add_verify(CLI::App& app) {
  auto* sub = app.add_subcommand("verify", "Check files: header, checksums, structure, or all");
  auto files = std::make_shared<std::vector<std::string>>();
  auto level = std::make_shared<std::string>("full");
  sub->add_option("FILE", *files, "the .mosb files to verify")->required();
  sub->add_option("--level", *level, "how much to check")
      ->check(CLI::IsMember({"header", "checksums", "structure", "full"}))
      ->capture_default_str();
  return {sub, [files, level] {
            const auto verify_level = *parse_verify_level(*level);
            int failures = 0;
            for (const auto& file : *files) {
              std::optional<std::string> problem;
              std::string digest;
              try {
                const auto reader = GraphReader::open(file);
                problem = verify(reader, verify_level);
                if (problem) problem = file + ": " + *problem;
                digest = reader.digest();
              } catch (const Error& e) {
                problem = e.what();
              }
              if (problem) {
                ++failures;
                std::cout << "FAIL " << *problem << '\n';
              } else {
                std::cout << "OK   " << file << " (" << *level << ", digest " << digest << ")\n";
              }
            }
            return failures == 0 ? 0 : 1;
          }};
}

}  // namespace mosb::cli
