// The CGAL translation unit(s) are kept few: CGAL headers compile slowly.
#include <CGAL/version.h>

#include "core/versions.hpp"

namespace streetgen::core {

std::string cgal_version() { return CGAL_VERSION_STR; }

}  // namespace streetgen::core
