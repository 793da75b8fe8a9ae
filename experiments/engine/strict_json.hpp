// The one JSON reader of every input (specs, results, cache records, shard manifests, benchmark
// output). Stricter than JSON itself where a lenient reading could change a number silently:
//   - a UTF-8 byte-order mark is refused (one spelling of a file, one hash of it);
//   - a key repeated in an object is refused (JSON lets the last one win without a word);
//   - a number too large for a double is refused (it would read as infinity);
//   - a control character (U+0000..U+001F, U+007F) in a key or a string is refused, also when
//     escaped, so no title, scene or reason can start a new line of a CSV header or a log;
//   - -0 reads as 0.
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string_view>

namespace mpmstab {

// Parses `text`, read from `file`. Throws InputError("<file>: <key path>: <what>"), the key path
// in the form cases[3].E.
template <class Json>
Json parse_json_strict(std::string_view text, const std::filesystem::path& file);

extern template nlohmann::json parse_json_strict<nlohmann::json>(std::string_view,
                                                                 const std::filesystem::path&);
extern template nlohmann::ordered_json parse_json_strict<nlohmann::ordered_json>(
    std::string_view, const std::filesystem::path&);

// read_input(file) then parse_json_strict: the whole of reading a JSON input.
nlohmann::ordered_json read_json_file(const std::filesystem::path& file);

}  // namespace mpmstab
