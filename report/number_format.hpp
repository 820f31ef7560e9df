// Numbers as the report's CSV and Markdown write them: printf formats, three significant digits
// for errors, percentages.
#pragma once

#include <string>

namespace toonwater::report {

std::string format(const char* spec, double value);  // snprintf(spec, value)
std::string g(double value);                         // "%.3g"
std::string percent(double share);                   // 0.123 -> "12.3 %"

}  // namespace toonwater::report
