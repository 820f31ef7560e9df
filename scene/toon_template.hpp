// templates/toon.inc, built into the program (templates.cpp.in), and the parts of it a scene
// uses.
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace toonwater {

// The text of templates/toon.inc.
std::string_view toon_template();

// templates/toon.inc with only the named parts ("bands", "flow", "objects", "outline",
// "silhouette"): what a scene directory gets, so it holds no macro its scene does not call.
std::string toon_template_parts(const std::vector<std::string>& parts);

}  // namespace toonwater
