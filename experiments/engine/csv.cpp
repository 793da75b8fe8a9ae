#include "csv.hpp"

#include "files.hpp"

#include <charconv>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace mpmstab {

namespace {

// Splits one record starting at `pos`; a quoted field may span lines.
std::vector<std::string> next_record(const std::string& text, std::size_t& pos, std::size_t& line,
                                     const std::filesystem::path& file) {
  std::vector<std::string> fields;
  std::string field;
  bool quoted = false;
  const std::size_t start_line = line;
  while (pos < text.size()) {
    const char ch = text[pos++];
    if (quoted) {
      if (ch == '"') {
        if (pos < text.size() && text[pos] == '"') {
          field += '"';
          ++pos;
        } else {
          quoted = false;
        }
      } else {
        if (ch == '\n') ++line;
        field += ch;
      }
    } else if (ch == '"') {
      quoted = true;
    } else if (ch == ',') {
      fields.push_back(std::move(field));
      field.clear();
    } else if (ch == '\n') {
      ++line;
      break;
    } else if (ch != '\r') {
      field += ch;
    }
  }
  if (quoted) {
    throw InputError(file, "line " + std::to_string(start_line) + ": unterminated quoted field");
  }
  fields.push_back(std::move(field));
  return fields;
}

}  // namespace

CsvTable read_csv(const std::filesystem::path& file) {
  const std::string text = read_input(file);
  CsvTable table;
  std::size_t pos = 0, line = 1;
  while (pos < text.size() && text[pos] == '#') {
    pos = text.find('\n', pos);
    pos = pos == std::string::npos ? text.size() : pos + 1;
    ++line;
  }
  if (pos >= text.size()) throw InputError(file, "no header line");
  table.header = next_record(text, pos, line, file);
  while (pos < text.size()) {
    const std::size_t record_line = line;
    auto fields = next_record(text, pos, line, file);
    if (fields.size() == 1 && fields[0].empty()) continue;  // blank line
    if (fields.size() != table.header.size()) {
      throw InputError(file, "line " + std::to_string(record_line) + ": " +
                                 std::to_string(fields.size()) + " fields, header has " +
                                 std::to_string(table.header.size()));
    }
    std::map<std::string, std::string> row;
    for (std::size_t i = 0; i < fields.size(); ++i)
      row[table.header[i]] = std::move(fields[i]);
    table.rows.push_back(std::move(row));
  }
  return table;
}

std::string shortest(double v) {
  char buf[64];
  const auto [end, ec] = std::to_chars(buf, buf + sizeof buf, v);
  return ec == std::errc() ? std::string(buf, end) : std::string("nan");
}

std::string csv_field(const std::string& s) {
  if (s.find_first_of(",\"\n\r") == std::string::npos) return s;
  std::string out = "\"";
  for (char c : s) {
    if (c == '"') out += '"';
    out += c;
  }
  return out + "\"";
}

}  // namespace mpmstab
