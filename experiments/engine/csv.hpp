// CSV: a reader for the reference tables (RFC 4180 quoting) and number formatting for writers.
#pragma once

#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace mpmstab {

struct CsvTable {
  std::vector<std::string> header;
  std::vector<std::map<std::string, std::string>> rows;  // column name -> field
};

// Reads a CSV file with a header line; lines starting with '#' before the header are skipped.
// Throws std::runtime_error naming the file and line on a malformed file.
CsvTable read_csv(const std::filesystem::path& file);

// Shortest text that reads back as the same double (std::to_chars).
std::string shortest(double v);

// A field quoted if it holds a comma, a quote or a line break.
std::string csv_field(const std::string& s);

}  // namespace mpmstab
