/* SPDX-License-Identifier: MPL-2.0 */
/* bench_stock.c -- removal throughput of the stock (not a ctest).
 *
 * A 3.175 mm ball (radius 1.5875 mm) sweeps a 2D zig-zag of N = 5000 moves of
 * 1 mm each, 1 mm deep into the top of an 80 x 80 x 20 mm box (each move a
 * capsule: distance to a segment minus the radius). For voxels of 0.1 and
 * 0.2 mm, one move at a time and in batches of 64 and 256; each run in its
 * own child process so that its peak RSS (getrusage) is its own.
 *
 * Usage: bench_stock [N]
 */
#include <stdio.h>
#include <stdlib.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "shapes.h"

static double now(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* Zig-zag: 1 mm moves along x from x = 5 to 75, 1 mm step-overs in y. */
static void make_path(capsule_shape *moves, int n) {
  const double r = 3.175 / 2.0, zc = -1.0 + r;
  double x = 5.0, y = 5.0;
  int dir = 1, along = 0;
  for (int i = 0; i < n; i++) {
    capsule_shape *c = &moves[i];
    c->a[0] = x, c->a[1] = y, c->a[2] = zc, c->r = r;
    if (along < 70)
      x += dir, along++;
    else
      y += 1.0, dir = -dir, along = 0;
    c->b[0] = x, c->b[1] = y, c->b[2] = zc;
  }
}

static int run(double voxel, int batch, int n) {
  const double lo[3] = {0, 0, -20}, hi[3] = {80, 80, 0};
  swarf_error err = {0};
  capsule_shape *moves = malloc(n * sizeof *moves);
  swarf_stock_cut *cuts = malloc(n * sizeof *cuts);
  make_path(moves, n);
  for (int i = 0; i < n; i++)
    cuts[i] = capsule_cut(&moves[i]);
  double t0 = now();
  swarf_stock *s = NULL;
  swarf_stock_new_box(lo, hi, voxel, 3, &s, &err);
  if (!s) return fprintf(stderr, "new_box: %s\n", err.message), 1;
  double t1 = now(), v0 = swarf_stock_volume(s);
  for (int i = 0; i < n; i += batch) {
    size_t k = (size_t)(n - i < batch ? n - i : batch);
    if (swarf_stock_remove_batch(s, cuts + i, k, &err) != 0)
      return fprintf(stderr, "remove: %s\n", err.message), 1;
  }
  double t2 = now(), removed = v0 - swarf_stock_volume(s);
  struct rusage ru;
  getrusage(RUSAGE_SELF, &ru);
  int valid = swarf_stock_check(s, &err) == 0;
  printf("voxel %.1f mm  batch %4d: %6d moves in %6.3f s = %8.0f moves/s  box %.2f s  "
         "removed %8.1f mm^3  active %9llu  peak RSS %5ld MB  %s\n",
         voxel, batch, n, t2 - t1, n / (t2 - t1), t1 - t0, removed, swarf_stock_active_voxels(s),
         ru.ru_maxrss / 1024, valid ? "valid" : err.message);
  fflush(stdout);
  swarf_stock_free(s);
  free(moves);
  free(cuts);
  return 0;
}

int main(int argc, char **argv) {
  int n = argc > 1 ? atoi(argv[1]) : 5000;
  const double voxels[2] = {0.2, 0.1};
  const int batches[3] = {1, 64, 256};
  for (int v = 0; v < 2; v++)
    for (int b = 0; b < 3; b++) {
      pid_t pid = fork();
      if (pid == 0) _exit(run(voxels[v], batches[b], n));
      int status = 0;
      waitpid(pid, &status, 0);
      if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) return 1;
    }
  return 0;
}
