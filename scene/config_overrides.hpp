// `--set key=value`: one override of the scene configuration, applied to the parsed TOML before
// the keys are read and validated (scene/config_schema.hpp), so an override meets the same
// checks as the file. The key is dotted: section.key, or object.N.key for the N-th object
// (counting from 0) of [[object]] and --object; the value is TOML, a bare word a string.
#pragma once

#include <toml++/toml.h>

#include <string>

namespace toonwater {

// Sets the key in `root`, creating its section when absent. Throws ConfigError naming the key
// for a malformed assignment, a key of the wrong depth or an object that does not exist.
void apply_override(toml::table& root, const std::string& assignment);

}  // namespace toonwater
