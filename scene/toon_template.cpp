// The parts of templates/toon.inc a scene uses. The template is a header, then parts that each
// start at a "// @part NAME" line, then "// @end" and a footer: the selection keeps the header,
// the parts named (in the template's order) and the footer.
#include "scene/toon_template.hpp"

#include <algorithm>
#include <stdexcept>

namespace toonwater {

std::string toon_template_parts(const std::vector<std::string>& parts) {
  const std::string_view text = toon_template();
  constexpr std::string_view part_marker = "// @part ", end_marker = "// @end";
  std::string out;
  std::string current;  // the part the line belongs to; empty: header or footer
  std::size_t found = 0;
  for (std::size_t begin = 0; begin < text.size();) {
    std::size_t end = text.find('\n', begin);
    end = end == std::string_view::npos ? text.size() : end + 1;
    const std::string_view line = text.substr(begin, end - begin);
    begin = end;
    if (line.starts_with(part_marker)) {
      current = std::string(line.substr(part_marker.size()));
      while (!current.empty() && (current.back() == '\n' || current.back() == '\r'))
        current.pop_back();
      found += std::count(parts.begin(), parts.end(), current) > 0;
      continue;
    }
    if (line.starts_with(end_marker)) {
      current.clear();
      continue;
    }
    if (current.empty() || std::count(parts.begin(), parts.end(), current) > 0) out += line;
  }
  if (found != parts.size()) throw std::logic_error("toon template: unknown part asked for");
  return out;
}

}  // namespace toonwater
