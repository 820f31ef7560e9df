// The guard in front of toml++, the scene configuration's parser.
//
// Two kinds of text break toml++ 3.3 (Debian 12's) instead of getting a parse error; both were
// found by fuzzing (tests/fuzz):
//  - a dotted key of some 10^5 components ("a.a.a... = 1", "[a.a.a...]"): toml++ nests a table
//    per component and walks and frees the nesting recursively, which overflows the stack;
//  - a non-ASCII character outside a string or comment, or inside a multi-line basic string:
//    toml++'s whitespace test reaches __builtin_unreachable for many code points (é, for one),
//    which is undefined behaviour (marzer/tomlplusplus issues 190 and 295).
// A scene configuration needs neither: its keys nest three levels at most, and TOML keeps
// non-ASCII text to strings and comments. So parse_toml first scans the text: strings (a quote
// opens one only where TOML expects a key or a value) and comments are skipped, the dots of each
// run of key components counted, and non-ASCII bytes rejected where toml++ would classify them.
// As the scan cannot tell strings apart in text that is not TOML, toml++ then parses a copy with
// every non-ASCII byte replaced by '?', which is valid only inside strings and comments: only
// text that passes both reaches toml++ as it is. Values cannot nest deeper than toml++'s own
// limit (TOML_MAX_NESTED_VALUES) with at most max_key_depth levels each.
#pragma once

#include <toml++/toml.h>

#include <string>
#include <string_view>

namespace toonwater {

// Keys nest at most this many levels (a scene configuration needs three).
inline constexpr int max_key_depth = 16;

// Throws ConfigError "WHERE:LINE: problem" for text toml++ must not parse.
void check_before_parsing(std::string_view text, const std::string& where);

// TOML text parsed by toml++ once nothing in it can break toml++. Throws ConfigError or
// toml::parse_error.
toml::table parse_toml(std::string_view text, std::string_view source);

}  // namespace toonwater
