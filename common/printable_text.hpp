// Text from outside the program (a file's field, a command-line word, a library's message) as
// part of one line of a message: printable ASCII is kept, every other byte (control characters,
// UTF-8, binary) is shown as '?', and "..." follows the first `longest` characters, so that a
// hostile value can neither break the line nor flood the terminal.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

namespace toonwater {

inline std::string printable_text(std::string_view text, std::size_t longest) {
  std::string out;
  for (const char c : text.substr(0, longest)) out += c >= ' ' && c <= '~' ? c : '?';
  if (text.size() > longest) out += "...";
  return out;
}

}  // namespace toonwater
