#include "core/versions.hpp"

#include <geos_c.h>

namespace streetgen::core {

std::string geos_runtime_version() { return GEOSversion(); }

}  // namespace streetgen::core
