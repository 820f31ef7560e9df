// The keys of scene.toml as a table: each key written once, with how its value is read (type and
// range), its default and a line of help. Reading a section walks the table; config_keys() lists
// it for the documentation, whose key table a test checks against it.
//
// A value's default is the one in config.hpp's structs (shown from a default-constructed
// section), or, for a key whose default depends on other values, a line saying what decides it.
// Rules that tie keys of one section together (t_medium < t_bright, position excludes
// direction, ...) run after the section's keys are read.
#pragma once

#include "scene/config.hpp"

#include <toml++/toml.h>

#include <string>

namespace toonwater {

// "FILE:LINE: " for a node read from a file; "" for one that --set made.
std::string source_location(const toml::node& node);

// Reads the root table's section `name` into `config`. Throws ConfigError for a section that
// does not exist, a key it does not have and a value of the wrong type or range ("FILE:LINE:
// config: 'section.key' ..." where the value comes from a file).
void read_section(const std::string& name, const toml::node& node, SceneConfig& config);

// One [[object]] table; `prefix` ("object.2") names its keys in errors.
ObjectConfig read_object(const toml::node& node, const std::string& prefix);

}  // namespace toonwater
