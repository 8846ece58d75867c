/* LD_PRELOAD'ed into a peer: at exit, appends its peak private memory to $PRIVATE_PEAK_OUT:
 * VmHWM - RssFile - RssShmem (peak resident memory without mapped files such as shared
 * libraries, read at the end). A peer maps no shared memory that grows after its peak, so this is
 * its private peak (or a little above, should file pages have been dropped since); the backend,
 * which keeps touching shared buffers, is sampled instead (bench/anon_peak.sh). With
 * /usr/bin/time's peak RSS alone, a peer's libraries counted against it and not against us. */
#include <stdio.h>
#include <stdlib.h>

__attribute__((destructor)) static void report_private_peak(void) {
  const char* out = getenv("PRIVATE_PEAK_OUT");
  FILE* status = fopen("/proc/self/status", "r");
  char line[256];
  long hwm = -1, file = 0, shmem = 0;
  if (out == NULL || status == NULL) return;
  while (fgets(line, sizeof line, status)) {
    sscanf(line, "VmHWM: %ld", &hwm);
    sscanf(line, "RssFile: %ld", &file);
    sscanf(line, "RssShmem: %ld", &shmem);
  }
  fclose(status);
  FILE* f = fopen(out, "a");
  if (f == NULL || hwm < 0) return;
  fprintf(f, "%ld\n", hwm - file - shmem);
  fclose(f);
}
