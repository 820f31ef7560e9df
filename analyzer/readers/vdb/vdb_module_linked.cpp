// vdb_module() for programs linked with the mesher itself (tests): see vdb_module.hpp.
#include "analyzer/readers/vdb/vdb_module.hpp"

namespace toonwater {

const VdbModule& vdb_module() { return *toonwater_vdb_module_entry(); }

}  // namespace toonwater
