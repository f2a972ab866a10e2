/* Memory bandwidth of one process: the STREAM triad a[i] = b[i] + s c[i] (McCalpin, "Memory
 * bandwidth and machine balance in current high performance computers", IEEE TCCA Newsletter,
 * 1995) over arrays far larger than any cache. Prints the median and the best of 20 passes in GB/s,
 * counting 24 bytes per element (two reads and one write, as STREAM does). Started as
 * `mpirun -np K stream_triad` it measures what each of K processes gets while all stream at once.
 * Usage: stream_triad [ELEMENTS] (default 2^25 per array, 768 MiB in all). */
#define _POSIX_C_SOURCE 199309L /* clock_gettime, CLOCK_MONOTONIC under -std=c99 */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <time.h>

static double now(void) {
  struct timespec t;
  clock_gettime(CLOCK_MONOTONIC, &t);
  return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

static int by_value(const void* a, const void* b) {
  const double x = *(const double*)a, y = *(const double*)b;
  return (x > y) - (x < y);
}

int main(int argc, char** argv) {
  enum { kPasses = 20 };
  const unsigned long long requested = argc > 1 ? strtoull(argv[1], NULL, 10) : 1ull << 25;
  if (requested == 0 || requested > SIZE_MAX / (3 * sizeof(double))) {
    fprintf(stderr, "stream_triad: ELEMENTS must be a count from 1 to %zu\n", SIZE_MAX / (3 * sizeof(double)));
    return 1;
  }
  const size_t n = (size_t)requested;
  double* a = malloc(n * sizeof *a);
  double* b = malloc(n * sizeof *b);
  double* c = malloc(n * sizeof *c);
  if (!a || !b || !c) {
    fprintf(stderr, "stream_triad: cannot hold 3 x %zu doubles\n", n);
    return 1;
  }
  for (size_t i = 0; i < n; ++i) a[i] = 0.0, b[i] = 1.0, c[i] = 2.0;  /* first touch: pages local */
  double seconds[kPasses];
  for (int p = 0; p < kPasses; ++p) {
    const double t0 = now();
    for (size_t i = 0; i < n; ++i) a[i] = b[i] + 3.0 * c[i];
    seconds[p] = now() - t0;
  }
  qsort(seconds, kPasses, sizeof seconds[0], by_value);
  const double bytes = 24.0 * (double)n;
  /* a[n/2] printed so that the passes cannot be optimised away */
  printf("triad_gb_s_median=%.2f triad_gb_s_best=%.2f check=%g\n", 1e-9 * bytes / seconds[kPasses / 2],
         1e-9 * bytes / seconds[0], a[n / 2]);
  free(a), free(b), free(c);
  return 0;
}
