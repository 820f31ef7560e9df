// Option checks shared by the subcommands. Every message they give is one printable line: a
// value the user typed is shown with control and non-ASCII bytes as '?'.
#pragma once

#include <CLI/CLI.hpp>

#include <string>
#include <utility>
#include <vector>

namespace toonwater::cli {

// The value shown in a message: at most 40 characters, control and non-ASCII bytes as '?'.
std::string printable_value(const std::string& value);

// A finite number: rejects "nan", "inf" and numbers too large for a double. PositiveNumber also
// asks for a sign (CLI11's own says "not in range 0.000000 to 1797693...", 309 digits).
extern const CLI::Validator FiniteNumber;
extern const CLI::Validator PositiveNumber;

// A file or directory name: refuses the empty string, which names no file (an unset shell
// variable in `--csv "$OUT"`), where it would otherwise read as the option left out.
extern const CLI::Validator NonEmptyPath;

// One of the given words, spelt exactly as the scene's keys take them (scene/config_schema.hpp),
// turned into the enum's value for CLI11 to store. Its description and errors list the words,
// never the enum's raw values.
template <class Enum>
CLI::Validator one_of(std::vector<std::pair<std::string, Enum>> choices) {
  std::string names;
  for (const auto& choice : choices) names += (names.empty() ? "" : ", ") + choice.first;
  return CLI::Validator(
      [choices, names](std::string& value) -> std::string {
        for (const auto& [name, v] : choices)
          if (name == value) {
            value = std::to_string(static_cast<int>(v));
            return {};
          }
        return "'" + printable_value(value) + "' is not one of " + names;
      },
      "one of: " + names);
}

}  // namespace toonwater::cli
