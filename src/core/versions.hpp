#pragma once
#include "core/no_postgres.hpp"

#include <string>

namespace streetgen::core {

std::string geos_runtime_version();  // of the libgeos_c actually loaded
std::string cgal_version();          // compiled in (CGAL is header-only)

}  // namespace streetgen::core
