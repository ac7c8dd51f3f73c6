/* SPDX-License-Identifier: MPL-2.0 */
/* bench_sweep.c -- time swarf_sweep_sdf per move kind over a grid of points
 * around a typical move (3.175 mm ball unless named, 1 mm of tip path), next
 * to the brute-force baseline: the minimum over 1001 cutter instances (1 um
 * apart), as a stamping simulator would do. Not a test; prints ns/eval.
 */
#define _POSIX_C_SOURCE 200809L /* clock_gettime */

#include <math.h>
#include <stdio.h>
#include <time.h>

#include "engine_private.h" /* the sweep's typed data */
#include "testkit.h"

#define GRID 40       /* points per axis for the evaluators */
#define BRUTE_GRID 12 /* points per axis for the baseline */
#define BRUTE_N 1000  /* instances of the baseline */

static double now(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

static volatile double sink;

static void grid_point(const double lo[3], const double hi[3], int n, int i, int j, int k,
                       double p[3]) {
  int ijk[3] = {i, j, k};
  for (int d = 0; d < 3; d++)
    p[d] = lo[d] - 1.0 + (hi[d] - lo[d] + 2.0) * (ijk[d] + 0.5) / n;
}

static double time_sdf(const swarf_sweep *s, const double lo[3], const double hi[3]) {
  double t0, acc = 0.0, p[3], best = INFINITY;
  for (int rep = 0; rep < 5; rep++) {
    t0 = now();
    for (int i = 0; i < GRID; i++)
      for (int j = 0; j < GRID; j++)
        for (int k = 0; k < GRID; k++) {
          grid_point(lo, hi, GRID, i, j, k, p);
          acc += swarf_sweep_sdf(s, p, NULL);
        }
    best = fmin(best, (now() - t0) / (GRID * GRID * GRID) * 1e9);
  }
  sink = acc;
  return best;
}

static double time_brute(const swarf_cutter *c, const swarf_motion *m, const double lo[3],
                         const double hi[3]) {
  double t0 = now(), acc = 0.0, p[3];
  for (int i = 0; i < BRUTE_GRID; i++)
    for (int j = 0; j < BRUTE_GRID; j++)
      for (int k = 0; k < BRUTE_GRID; k++) {
        double best = INFINITY;
        grid_point(lo, hi, BRUTE_GRID, i, j, k, p);
        for (int a = 0; a <= BRUTE_N; a++)
          best = fmin(best, tk_instance(c, m, p, (double)a / BRUTE_N));
        acc += best;
      }
  sink = acc;
  return (now() - t0) / (BRUTE_GRID * BRUTE_GRID * BRUTE_GRID) * 1e9;
}

static void run(const char *name, const swarf_cutter *c, swarf_motion m) {
  swarf_sweep s;
  double lo[3], hi[3], fast, slow;
  swarf_sweep_init(&s, c, &m);
  swarf_sweep_bounds(&s, lo, hi);
  fast = time_sdf(&s, lo, hi);
  slow = time_brute(c, &m, lo, hi);
  printf("%-22s method %d  %8.1f ns/eval   brute(%d) %10.0f ns/eval   x%.0f\n", name,
         swarf_sweep_cdata(&s)->method, fast, BRUTE_N + 1, slow, slow / fast);
}

int main(void) {
  swarf_cutter ball, flat, bull;
  const double o[3] = {0, 0, 0}, x1[3] = {1, 0, 0}, z1[3] = {0, 0, -1};
  const double ramp[3] = {0.8, 0.3, -0.52}, up[3] = {0, 0, 1}, ny[3] = {0, 1, 0};
  const double c2[3] = {-2, 0, 0}, ring_c[3] = {-1 / (2 * tk_pi), 0, 0}, c18[3] = {-2, 0, 0};
  swarf_cutter_init(&ball, SWARF_CUTTER_BALL, 3.175, 0, 0, NULL);
  swarf_cutter_init(&flat, SWARF_CUTTER_FLAT, 3.175, 0, 0, NULL);
  swarf_cutter_init(&bull, SWARF_CUTTER_BULL, 3.175, 0.5, 0, NULL);
  printf("ball D 3.175, 1 mm moves, %d^3 grid over the bounds + 1 mm\n", GRID);
  run("slot (ball)", &ball, tk_line(o, x1));
  run("plunge (ball)", &ball, tk_line(o, z1));
  run("ramp (ball)", &ball, tk_line(o, ramp));
  run("ramp (flat)", &flat, tk_line(o, ramp));
  run("ramp (bull)", &bull, tk_line(o, ramp));
  run("arc (ball)", &ball, tk_helix(o, c2, up, 0.5, 0.0));
  run("ring (ball)", &ball, tk_helix(o, ring_c, up, 2 * tk_pi, 0.0));
  run("helix (ball)", &ball, tk_helix(o, c2, up, 0.4, -0.6));
  run("G18 arc (ball)", &ball, tk_helix(o, c18, ny, 0.5, 0.0));
  run("helix (flat)", &flat, tk_helix(o, c2, up, 0.4, -0.6));
  return 0;
}
