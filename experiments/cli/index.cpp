// `mpmstab index`: results/README.md, the index of the reports.
#include <iostream>

#include "commands.hpp"
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
  write_index(specs, output_folder(args));
  return 0;
}

}  // namespace mpmstab::cli
