#include "cli/analysis_options.hpp"

#include "cli/validators.hpp"

#include <cctype>
#include <cstdlib>
#include <optional>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace toonwater::cli {
namespace {

// A number typed for `setting`, refused in the words a scene's key gets (config_schema.cpp). A
// whole number is handed on as its digits, so that 2.0 is taken as 2, as a scene takes it.
CLI::Validator number_check(const AnalysisSetting& setting) {
  return CLI::Validator(
      [&setting](std::string& value) -> std::string {
        char* end = nullptr;
        const double number = std::strtod(value.c_str(), &end);
        std::string why;
        if (value.empty() || end != value.c_str() + value.size())
          why = setting.is_whole_number() ? "must be a whole number" : "must be a number";
        else
          why = setting.refusal(number);
        if (!why.empty()) return "'" + printable_value(value) + "' " + why;
        if (setting.is_whole_number()) value = std::to_string(static_cast<int>(number));
        return {};
      },
      setting.type());
}

template <class T>
struct is_optional : std::false_type {};
template <class T>
struct is_optional<std::optional<T>> : std::true_type {};

std::string sentence(std::string help) {
  if (!help.empty()) help[0] = static_cast<char>(std::toupper(static_cast<unsigned char>(help[0])));
  return help;
}

}  // namespace

void add_analysis_options(CLI::App& cmd, AnalysisSettings& settings) {
  for (const AnalysisSetting& setting : analysis_settings()) {
    std::visit(
        [&](auto member) {
          auto& value = settings.*member;
          using T = std::remove_reference_t<decltype(value)>;
          // A default that depends on other settings is told in the help, a value after the type.
          const bool unset = is_optional<T>::value;
          CLI::Option* option = cmd.add_option(
              "--" + setting.option, value,
              sentence(setting.help) + (unset ? " (default: " + setting.default_value + ")" : ""));
          if (!unset) option->default_str(setting.default_value);
          if constexpr (std::is_enum_v<T>) {
            std::vector<std::pair<std::string, T>> choices;
            for (const auto& [word, enum_value] : setting.words)
              choices.emplace_back(word, static_cast<T>(enum_value));
            option->transform(one_of<T>(choices));
          } else {
            option->transform(number_check(setting));
          }
        },
        setting.member);
  }
}

}  // namespace toonwater::cli
