// Every src/core header includes this first. src/core is pure C++17 and must build without
// PostgreSQL. In src/pg, core, STL and CGAL headers must come before PostgreSQL's, whose
// Min/Max/snprintf/gettext macros break CGAL and the standard library: this guard turns the
// wrong include order into a compile error instead of a puzzling template failure.
#pragma once

#if defined(POSTGRES_H) || defined(C_H) || defined(PG_VERSION_NUM)
#error "A PostgreSQL header was included before a streetgen core header; include core/STL/CGAL headers first."
#endif
