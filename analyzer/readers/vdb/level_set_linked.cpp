// level_set_module() for programs linked with the mesher itself (tests): see level_set_module.hpp.
#include "analyzer/readers/vdb/level_set_module.hpp"

namespace toonwater {

const LevelSetModule& level_set_module() { return *toonwater_level_set_module_entry(); }

}  // namespace toonwater
