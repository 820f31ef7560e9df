#include "cli/validators.hpp"

#include "common/printable_text.hpp"

#include <cmath>
#include <cstdlib>

namespace toonwater::cli {

std::string printable_value(const std::string& value) {
  constexpr std::size_t longest_value_shown = 40;
  return printable_text(value, longest_value_shown);
}

namespace {

// A validator accepting finite numbers for which `accept` holds; `what` names them in errors.
CLI::Validator finite_number(bool (*accept)(double), const char* what) {
  return CLI::Validator(
      [accept, what](std::string& value) -> std::string {
        char* end = nullptr;
        const double number = std::strtod(value.c_str(), &end);
        if (value.empty() || end != value.c_str() + value.size() || !std::isfinite(number) ||
            !accept(number))
          return "'" + printable_value(value) + "' is not " + what;
        return {};
      },
      "");
}

}  // namespace

const CLI::Validator FiniteNumber = finite_number([](double) { return true; }, "a finite number");
const CLI::Validator PositiveNumber =
    finite_number([](double v) { return v > 0; }, "a positive finite number");

const CLI::Validator NonEmptyPath = CLI::Validator(
    [](std::string& value) -> std::string {
      return value.empty() ? "an empty path names no file" : std::string{};
    },
    "");

}  // namespace toonwater::cli
