#include "pg/boundary.hpp"
#include "pg/postgres_headers.hpp"

extern "C" {
PG_MODULE_MAGIC;

PGDLLEXPORT void _PG_init(void);
void _PG_init(void) { streetgen::pg::install_interrupt_hooks(); }
}
