// PostgreSQL's headers for C++ translation units. Include this last: core, STL and CGAL headers
// first (core/no_postgres.hpp enforces it). The headers are C, hence extern "C".
#pragma once

extern "C" {
#include "postgres.h"

#include "access/htup_details.h"
#include "fmgr.h"
#include "funcapi.h"
#include "miscadmin.h"
#include "utils/builtins.h"
#include "utils/memutils.h"
#include "utils/tuplestore.h"
}
