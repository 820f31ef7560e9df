#include "report/number_format.hpp"

#include <cstdio>

namespace toonwater::report {

std::string format(const char* spec, double value) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, spec, value);
  return buffer;
}

std::string g(double value) { return format("%.3g", value); }

std::string percent(double share) { return format("%.1f %%", 100.0 * share); }

}  // namespace toonwater::report
