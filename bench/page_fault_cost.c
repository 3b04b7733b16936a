/* What one page fault costs on this machine (docs/sweeps.md, "Speed"): 1000 pages touched once
 * each, fresh (zero-filled on first write) and, in a forked child, copy-on-write; then the same
 * number of copy-on-write pages populated by one madvise(MADV_POPULATE_WRITE) call (Linux 5.14).
 *
 *   cc -O2 bench/page_fault_cost.c -o /tmp/page_fault_cost && /tmp/page_fault_cost
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

enum { kPages = 1000, kPage = 4096 };

static double now(void) {
  struct timespec t;
  clock_gettime(CLOCK_MONOTONIC, &t);
  return t.tv_sec + 1e-9 * t.tv_nsec;
}

static char* pages(void) {
  return mmap(NULL, (size_t)kPages * kPage, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1,
              0);
}

int main(void) {
  char *written = pages(), *populated = pages(), *fresh = pages();
  memset(written, 1, (size_t)kPages * kPage);
  memset(populated, 1, (size_t)kPages * kPage);
  double t = now();
  for (size_t i = 0; i < (size_t)kPages * kPage; i += kPage) fresh[i] = 1;
  printf("fresh page, first write:      %6.2f us\n", (now() - t) / kPages * 1e6);
  fflush(stdout);
  if (fork() == 0) {
    t = now();
    for (size_t i = 0; i < (size_t)kPages * kPage; i += kPage) written[i] = 2;
    printf("copy-on-write, first write:   %6.2f us\n", (now() - t) / kPages * 1e6);
#ifdef MADV_POPULATE_WRITE
    t = now();
    madvise(populated, (size_t)kPages * kPage, MADV_POPULATE_WRITE);
    printf("copy-on-write, one madvise:   %6.2f us a page\n", (now() - t) / kPages * 1e6);
#endif
    fflush(stdout);
    _exit(0);
  }
  wait(NULL);
  return 0;
}
