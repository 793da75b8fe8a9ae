// Generated blocks of the project's documents (README.md, docs/theory.md, docs/studies.md). A
// passage of a document that states a result is not typed by hand: it lies between the markers
//   <!-- generated: NAME (mpmstab documents writes this block from results/; do not edit) -->
//   ...
//   <!-- end generated: NAME -->
// and is rendered from the results folder by the code that renders the reports (`mpmstab
// documents`, run by make reproduce and make studies). `mpmstab documents --check` (run by make
// check) fails where a block differs from what the results give: edited by hand, or left behind
// when a result changed.
#pragma once

#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace mpmstab {

// Every block the documents may hold, by name, rendered from `results`. A block whose results
// are missing renders as a sentence that says which and how to make them.
std::map<std::string, std::string> document_blocks(const std::filesystem::path& results);

// `text` with each marked block replaced by its rendering; `found` lists the names in order.
// Throws InputError naming `file` for an unknown name, an end marker missing or out of order.
std::string fill_document(const std::string& text, const std::map<std::string, std::string>& blocks,
                          const std::string& file, std::vector<std::string>* found = nullptr);

}  // namespace mpmstab
