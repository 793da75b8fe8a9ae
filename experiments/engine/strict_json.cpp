#include "strict_json.hpp"

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

std::string path_of(const std::vector<Frame>& frames) {
  std::string path;
  for (const Frame& f : frames) {
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

// Refuses control characters in strings and turns -0 into 0, walking the parsed tree.
template <class Json>
void check_values(Json& v, const std::string& path, const std::filesystem::path& file) {
  if (v.is_string()) {
    if (const auto c = control_character(v.template get_ref<const std::string&>()); !c.empty()) {
      throw InputError(file, at(path) + "contains the control character " + c +
                                 " (a line break or tab may not appear in a string)");
    }
  } else if (v.is_number_float()) {
    if (v.template get<double>() == 0.0) v = 0.0;
  } else if (v.is_array()) {
    for (std::size_t i = 0; i < v.size(); ++i)
      check_values(v[i], path + "[" + std::to_string(i) + "]", file);
  } else if (v.is_object()) {
    for (auto it = v.begin(); it != v.end(); ++it) {
      const std::string here = path.empty() ? it.key() : path + "." + it.key();
      if (const auto c = control_character(it.key()); !c.empty()) {
        throw InputError(file, at(path) + "a key contains the control character " + c);
      }
      check_values(it.value(), here, file);
    }
  }
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

template <class Json>
Json parse_json_strict(std::string_view text, const std::filesystem::path& file) {
  if (text.starts_with("\xEF\xBB\xBF")) {
    throw InputError(file, "starts with a UTF-8 byte-order mark; save it without one");
  }
  std::vector<Frame> frames;
  using Event = nlohmann::json::parse_event_t;
  auto after_value = [&frames] {
    if (!frames.empty() && !frames.back().object) ++frames.back().index;
  };
  const auto callback = [&](int, Event event, Json& parsed) {
    switch (event) {
      case Event::object_start:
        frames.push_back(Frame{true, {}, {}, 0});
        break;
      case Event::array_start:
        frames.push_back(Frame{false, {}, {}, 0});
        break;
      case Event::key: {
        Frame& f = frames.back();
        const auto& key = parsed.template get_ref<const std::string&>();
        for (const auto& seen : f.keys) {
          if (seen == key) {
            f.key = key;
            throw InputError(file, path_of(frames) +
                                       ": is given twice in one object (JSON would keep the "
                                       "last one without a word)");
          }
        }
        f.keys.push_back(key);
        f.key = key;
        break;
      }
      case Event::object_end:
      case Event::array_end:
        frames.pop_back();
        after_value();
        break;
      case Event::value:
        after_value();
        break;
    }
    return true;
  };
  try {
    Json doc = Json::parse(text.begin(), text.end(), callback);
    check_values(doc, "", file);
    return doc;
  } catch (const nlohmann::json::parse_error& e) {
    malformed(text, file, e);
  } catch (const nlohmann::json::exception& e) {
    // For example a number that overflows a double ("1e999").
    std::string what = e.what();
    if (const auto where = what.find("] "); where != std::string::npos) {
      what = what.substr(where + 2);
    }
    throw InputError(file, at(path_of(frames)) + "malformed JSON: " + what);
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
