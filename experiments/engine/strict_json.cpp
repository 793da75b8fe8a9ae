#include "strict_json.hpp"

#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

#include "files.hpp"

namespace mpmstab {

namespace {

// Where the parser is: one frame per open object or array.
struct Frame {
  bool object = false;
  std::vector<std::string> keys;  // seen in this object (objects are small: a scan is enough)
  std::string key;                // the current key of an object
  std::size_t index = 0;          // the current element of an array
};

// The path of the value being read in the form cases[3].E, through the first `depth` frames
// (all of them by default; one fewer: the path of the innermost object or array itself).
std::string path_of(const std::vector<Frame>& frames, std::size_t depth = SIZE_MAX) {
  std::string path;
  for (std::size_t i = 0; i < frames.size() && i < depth; ++i) {
    const Frame& f = frames[i];
    if (f.object) {
      if (f.key.empty() && f.keys.empty()) continue;
      if (!path.empty()) path += '.';
      path += f.key;
    } else {
      path += '[';
      path += std::to_string(f.index);
      path += ']';
    }
  }
  return path;
}

std::string at(const std::string& path) {
  return path.empty() ? "" : path + ": ";
}

// The first control character of `s`, as "U+000A", or "".
std::string control_character(const std::string& s) {
  for (const unsigned char c : s) {
    if (c < 0x20 || c == 0x7f) {
      char buf[8];
      std::snprintf(buf, sizeof buf, "U+%04X", static_cast<unsigned>(c));
      return buf;
    }
  }
  return "";
}

[[noreturn]] void malformed(std::string_view text, const std::filesystem::path& file,
                            const nlohmann::json::parse_error& e) {
  // Line and column of the byte where parsing stopped.
  std::size_t line = 1, column = 1;
  for (std::size_t i = 0; i + 1 < e.byte && i < text.size(); ++i) {
    if (text[i] == '\n') {
      ++line;
      column = 1;
    } else {
      ++column;
    }
  }
  std::string what = e.what();
  if (const auto where = what.find("syntax error"); where != std::string::npos) {
    what = what.substr(where);
  }
  throw InputError(file, "malformed JSON at line " + std::to_string(line) + ", column " +
                             std::to_string(column) + ": " + what);
}

}  // namespace

// nlohmann's DOM builder behind a SAX interface that keeps the frames (for the path of a message)
// and checks each key and value as it is read: a repeated key and a control character are
// refused, -0 becomes 0. nlohmann's own callback parser rescans the parent array each time an
// element ends (to drop discarded values), time quadratic in the length of a history; this
// builder does not rescan, and nothing walks the document again after it is read.
template <class Json>
class StrictSax {
 public:
  using number_integer_t = typename Json::number_integer_t;
  using number_unsigned_t = typename Json::number_unsigned_t;
  using number_float_t = typename Json::number_float_t;
  using string_t = typename Json::string_t;
  using binary_t = typename Json::binary_t;

  StrictSax(Json& doc, const std::filesystem::path& file) : dom_(doc, true), file_(file) {}

  const std::vector<Frame>& frames() const { return frames_; }

  bool null() { return value(dom_.null()); }
  bool boolean(bool b) { return value(dom_.boolean(b)); }
  bool number_integer(number_integer_t n) { return value(dom_.number_integer(n)); }
  bool number_unsigned(number_unsigned_t n) { return value(dom_.number_unsigned(n)); }
  bool number_float(number_float_t x, const string_t& s) {
    return value(dom_.number_float(x == 0.0 ? 0.0 : x, s));  // -0 reads as 0
  }
  bool string(string_t& s) {
    if (const auto c = control_character(s); !c.empty()) {
      throw InputError(file_, at(path_of(frames_)) + "contains the control character " + c +
                                  " (a line break or tab may not appear in a string)");
    }
    return value(dom_.string(s));
  }
  bool binary(binary_t& b) { return value(dom_.binary(b)); }
  bool start_object(std::size_t n) {
    frames_.push_back(Frame{true, {}, {}, 0});
    return dom_.start_object(n);
  }
  bool key(string_t& k) {
    if (const auto c = control_character(k); !c.empty()) {
      throw InputError(file_, at(path_of(frames_, frames_.size() - 1)) +
                                  "a key contains the control character " + c);
    }
    Frame& f = frames_.back();
    for (const auto& seen : f.keys) {
      if (seen == k) {
        f.key = k;
        throw InputError(file_, path_of(frames_) +
                                    ": is given twice in one object (JSON would keep the "
                                    "last one without a word)");
      }
    }
    f.keys.push_back(k);
    f.key = k;
    return dom_.key(k);
  }
  bool end_object() { return end(dom_.end_object()); }
  bool start_array(std::size_t n) {
    frames_.push_back(Frame{false, {}, {}, 0});
    return dom_.start_array(n);
  }
  bool end_array() { return end(dom_.end_array()); }
  template <class Exception>
  bool parse_error(std::size_t position, const std::string& token, const Exception& e) {
    return dom_.parse_error(position, token, e);  // throws e
  }

 private:
  bool value(bool ok) {  // a value is complete: the next element of an array
    if (!frames_.empty() && !frames_.back().object) ++frames_.back().index;
    return ok;
  }
  bool end(bool ok) {
    frames_.pop_back();
    return value(ok);
  }

  nlohmann::detail::json_sax_dom_parser<Json> dom_;
  const std::filesystem::path& file_;
  std::vector<Frame> frames_;
};

template <class Json>
Json parse_json_strict(std::string_view text, const std::filesystem::path& file) {
  if (text.starts_with("\xEF\xBB\xBF")) {
    throw InputError(file, "starts with a UTF-8 byte-order mark; save it without one");
  }
  Json doc;
  StrictSax<Json> sax(doc, file);
  try {
    Json::sax_parse(text.begin(), text.end(), &sax);
    return doc;
  } catch (const nlohmann::json::parse_error& e) {
    malformed(text, file, e);
  } catch (const nlohmann::json::exception& e) {
    // For example a number that overflows a double ("1e999").
    std::string what = e.what();
    if (const auto where = what.find("] "); where != std::string::npos) {
      what = what.substr(where + 2);
    }
    throw InputError(file, at(path_of(sax.frames())) + "malformed JSON: " + what);
  }
}

template nlohmann::json parse_json_strict<nlohmann::json>(std::string_view,
                                                          const std::filesystem::path&);
template nlohmann::ordered_json parse_json_strict<nlohmann::ordered_json>(
    std::string_view, const std::filesystem::path&);

nlohmann::ordered_json read_json_file(const std::filesystem::path& file) {
  return parse_json_strict<nlohmann::ordered_json>(read_input(file), file);
}

}  // namespace mpmstab
