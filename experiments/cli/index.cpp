// `mpmstab index`: results/README.md, the index of the reports.
#include <iostream>

#include "commands.hpp"
#include "files.hpp"
#include "report.hpp"

namespace mpmstab::cli {

namespace {

constexpr const char* kIndexHelp = R"(Usage: mpmstab index <spec.json>... [--out DIR]

Writes DIR/README.md (default results/README.md), the index of the reports of the given specs.
)";

}  // namespace

int cmd_index(const std::vector<std::string_view>& argv) {
  const Args args(argv, {{"out"}, {"help", false}});
  if (args.flag("help")) {
    std::cout << kIndexHelp;
    return 0;
  }
  const auto specs = load_specs(args.positional());
  const auto out = output_folder(args);
  finish_publications_in(out);  // a report set a killed run left half published
  write_index(specs, out);
  return 0;
}

}  // namespace mpmstab::cli
