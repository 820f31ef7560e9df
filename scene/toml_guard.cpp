#include "scene/toml_guard.hpp"

#include "scene/config.hpp"

#include <algorithm>
#include <cctype>

namespace toonwater {

void check_before_parsing(std::string_view text, const std::string& where) {
  std::size_t line = 1;
  const auto reject = [&](const std::string& problem) {
    throw ConfigError(where + ":" + std::to_string(line) + ": " + problem);
  };
  const auto is_ascii = [](char c) { return static_cast<unsigned char>(c) < 0x80; };
  int dots = 0;
  char last = '\n';  // the last character outside strings and comments, not counting blanks
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (c == '\n') ++line;
    const bool opens_string = (c == '"' || c == '\'') &&
                              std::string_view("\n\r.[{,=").find(last) != std::string_view::npos;
    if (c != ' ' && c != '\t') last = c;
    if (opens_string) {  // a string (perhaps a quoted key component): skip it
      const std::size_t quotes = text.substr(i, 3) == std::string(3, c) ? 3 : 1;
      const std::string_view close = text.substr(i, quotes);
      std::size_t j = i + quotes;
      for (; j < text.size() && text.substr(j, quotes) != close; ++j) {
        if (c == '"' && quotes == 3 && !is_ascii(text[j]))
          reject("non-ASCII text in a \"\"\" string (write it in \"...\" or '''...''')");
        if (c == '"' && text[j] == '\\' && j + 1 < text.size()) ++j;  // an escaped character
        if (text[j] == '\n') ++line;
      }
      i = j + quotes - 1;
    } else if (c == '#') {  // a comment: on to the end of the line
      i = std::min(text.find('\n', i), text.size()) - 1;
    } else if (c == '.') {
      if (++dots > max_key_depth)
        reject("keys nest more than " + std::to_string(max_key_depth) + " levels deep");
    } else if (!is_ascii(c)) {
      reject("non-ASCII character outside a string or comment");
    } else if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == ' ' ||
                 c == '\t')) {
      dots = 0;
    }
  }
}

toml::table parse_toml(std::string_view text, std::string_view source) {
  check_before_parsing(text, std::string(source));
  std::string masked(text);
  std::replace_if(
      masked.begin(), masked.end(), [](char c) { return static_cast<unsigned char>(c) >= 0x80; },
      '?');
  if (masked != text) static_cast<void>(toml::parse(masked, source));  // throws if not TOML
  return toml::parse(text, source);
}

}  // namespace toonwater
