// `mpmstab documents`: the generated blocks of README.md and docs/ (publish/
// documents.hpp), written from the results, or with --check compared with them.
#include <iostream>

#include "commands.hpp"
#include "files.hpp"
#include "publish/documents.hpp"

namespace mpmstab::cli {

namespace {

constexpr const char* kDocumentsHelp =
    R"(Usage: mpmstab documents <file>... [--results DIR] [--check]

Rewrites each generated block of the given documents (the text between
'<!-- generated: NAME ... -->' and '<!-- end generated: NAME -->') from the results in DIR
(default results), writing a document only where a block changed. With --check it writes
nothing, names every block that differs from what the results give, and exits with status 1
if one does. An unknown block name or a marker without its pair is refused (status 2).
)";

}  // namespace

int cmd_documents(const std::vector<std::string_view>& argv) {
  const Args args(argv, {{"results"}, {"check", false}, {"help", false}});
  if (args.flag("help")) {
    std::cout << kDocumentsHelp;
    return 0;
  }
  if (args.positional().empty()) throw UsageError("name at least one document");
  const std::filesystem::path results(std::string(args.value("results").value_or("results")));
  const auto blocks = document_blocks(results);
  // Read and fill every document first: a refused one leaves every file untouched.
  std::vector<std::pair<std::filesystem::path, std::string>> filled;
  int differ = 0;
  for (const auto& name : args.positional()) {
    const std::filesystem::path file{std::string(name)};
    const std::string text = read_input(file, kMaxInputBytes);
    std::vector<std::string> found;
    const std::string out = fill_document(text, blocks, file.string(), &found);
    if (out != text) {
      ++differ;
      if (args.flag("check"))
        std::cerr << "documents: " << file.string()
                  << ": a generated block differs from what the results give (run make "
                     "reproduce or make studies, not an edit by hand); blocks: "
                  << found.size() << "\n";
    }
    filled.emplace_back(file, out);
  }
  if (args.flag("check")) {
    if (differ == 0) std::cout << "documents: every generated block matches the results\n";
    return differ == 0 ? 0 : 1;
  }
  for (const auto& [file, text] : filled)
    write_if_changed(file, text);
  return 0;
}

}  // namespace mpmstab::cli
