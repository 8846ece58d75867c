#include <malloc.h>  // mallopt (glibc)

#include "pg/boundary.hpp"
#include "pg/postgres_headers.hpp"

extern "C" {
PG_MODULE_MAGIC;

PGDLLEXPORT void _PG_init(void);
void _PG_init(void) {
  streetgen::pg::install_interrupt_hooks();
  // glibc serves allocations of 128 KiB and more with their own mappings, returned to the
  // system when freed, but raises that threshold (up to 32 MiB) each time such a mapping is
  // freed; from then on the large buffers of a whole-city run (PostgreSQL's arrays of a city's
  // pieces for the blocks, GEOS's coordinate arrays) come from the heap, whose freed holes are
  // too small for the next ones. Pinned at glibc's own default, the backend's peak private
  // memory of one generate() (RssAnon, sampled) fell by 5-7 MB: Liechtenstein 56 -> 51 MB,
  // Baltimore 74 -> 67, Campo Grande 126 -> 121, Paris 363 -> 358 (Reisterstown 88 either way:
  // its peak is the engine's), for about 0.6 s more system time on Paris' 70 s.
  mallopt(M_MMAP_THRESHOLD, 128 * 1024);
}
}
