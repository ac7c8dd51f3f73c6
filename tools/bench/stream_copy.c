/* SPDX-License-Identifier: MPL-2.0 */
/* stream_copy.c -- the machine's memory bandwidth, as STREAM's Copy kernel
 * measures it: a[i] = b[i] over arrays far larger than the caches, on every
 * core, best of several rounds; bytes counted as STREAM does (read + write).
 *
 *   stream_copy [MB_PER_ARRAY [THREADS]]   prints "copy GB/s THREADS"
 *
 * tools/bench/bench_speed prints the removal's bytes per second against it.
 */
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

typedef struct {
  double *a, *b;
  size_t lo, hi;
  pthread_barrier_t *start;
  double t0, t1; /* this thread's copy, measured by itself (the main thread may wait
                  * for a core) */
} slice;

static double now(void) {
  struct timespec t;
  clock_gettime(CLOCK_MONOTONIC, &t);
  return t.tv_sec + 1e-9 * t.tv_nsec;
}

static void *copy(void *arg) {
  slice *s = arg;
  pthread_barrier_wait(s->start);
  s->t0 = now();
  memcpy(s->a + s->lo, s->b + s->lo, (s->hi - s->lo) * sizeof *s->a);
  s->t1 = now();
  return NULL;
}

int main(int argc, char **argv) {
  const size_t mb = argc > 1 ? strtoul(argv[1], NULL, 10) : 256;
  long nt = argc > 2 ? strtol(argv[2], NULL, 10) : sysconf(_SC_NPROCESSORS_ONLN);
  const size_t n = mb * 1024 * 1024 / sizeof(double);
  double *a = malloc(n * sizeof *a), *b = malloc(n * sizeof *b), best = 0.0;
  if (a == NULL || b == NULL || nt < 1 || nt > 256 || mb < 1) {
    fputs("stream_copy: usage: stream_copy [MB_PER_ARRAY [THREADS]]\n", stderr);
    return 2;
  }
  for (size_t i = 0; i < n; i++) /* touch every page: no first-touch faults in the timing */
    a[i] = 0.0, b[i] = (double)i;
  pthread_t th[256];
  slice sl[256];
  for (int round = 0; round < 6; round++) {
    pthread_barrier_t start;
    pthread_barrier_init(&start, NULL, (unsigned)nt + 1);
    for (long t = 0; t < nt; t++) {
      sl[t] = (slice){a,   b,  n * (size_t)t / (size_t)nt, n * (size_t)(t + 1) / (size_t)nt, &start,
                      0.0, 0.0};
      pthread_create(&th[t], NULL, copy, &sl[t]);
    }
    pthread_barrier_wait(&start);
    double t0 = 1e300, t1 = 0.0;
    for (long t = 0; t < nt; t++) {
      pthread_join(th[t], NULL);
      t0 = sl[t].t0 < t0 ? sl[t].t0 : t0;
      t1 = sl[t].t1 > t1 ? sl[t].t1 : t1;
    }
    const double gbs = 2.0 * n * sizeof(double) / (t1 - t0) / 1e9;
    pthread_barrier_destroy(&start);
    if (round > 0 && gbs > best) best = gbs; /* round 0 warms up */
  }
  const int same = a[n / 2] == b[n / 2]; /* the copy was made (and not optimised away) */
  printf("copy %.2f GB/s %ld\n", best, nt);
  free(a);
  free(b);
  return same ? 0 : 1;
}
