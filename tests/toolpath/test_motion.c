/* SPDX-License-Identifier: MPL-2.0 */
/* test_motion.c -- the xyz machine's rigid motions against hand-computed values:
 * line and helix positions, velocities by finite differences, bounds against
 * dense sampling; the per-thread pose tables against the motions' poses. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "move_motion.h"

static swarf_move make_arc(double cx, double cy, double sign, double angle, double rise) {
  swarf_move mv;
  memset(&mv, 0, sizeof mv);
  mv.kind = SWARF_MOVE_ARC;
  mv.start[0] = cx + 5.0;
  mv.start[1] = cy;
  mv.start[2] = -1.0;
  mv.center[0] = cx;
  mv.center[1] = cy;
  mv.center[2] = -1.0;
  mv.normal[2] = sign;
  mv.angle = angle;
  mv.rise = rise;
  mv.feed = 600.0;
  return mv;
}

static void test_line(void) {
  swarf_move mv;
  swarf_motion m;
  double t[3], U[9];
  memset(&mv, 0, sizeof mv);
  mv.kind = SWARF_MOVE_LINE;
  mv.end[0] = 3.0;
  mv.end[1] = 4.0;
  mv.feed = 300.0;
  CHECK(swarf_motion_from_move(&mv, &m, NULL) == SWARF_OK, "line accepted");
  swarf_motion_eval(&m, 0.5, t, U);
  CHECK_NEAR(t[0], 1.5, 1e-15, "line midpoint x");
  CHECK_NEAR(t[1], 2.0, 1e-15, "line midpoint y");
  CHECK(U[0] == 1 && U[4] == 1 && U[8] == 1 && U[1] == 0, "U is the identity");
  CHECK_NEAR(m.length, 5.0, 1e-15, "line length");
  CHECK_NEAR(m.duration, 1.0, 1e-12, "5 mm at 300 mm/min takes 1 s");
  mv.kind = SWARF_MOVE_DWELL;
  CHECK(swarf_motion_from_move(&mv, &m, NULL) == SWARF_ERR_ARG, "dwell is no motion");
}

static void test_helix_quarter(void) {
  /* G3 (normal +z) from (15,10) about (10,10), a quarter turn, rising 2 mm. */
  swarf_move mv = make_arc(10.0, 10.0, 1.0, M_PI / 2, 2.0);
  swarf_motion m;
  double t[3];
  CHECK(swarf_motion_from_move(&mv, &m, NULL) == SWARF_OK, "arc accepted");
  swarf_motion_eval(&m, 1.0, t, NULL);
  CHECK_NEAR(t[0], 10.0, 1e-12, "G3 quarter ends at x = 10");
  CHECK_NEAR(t[1], 15.0, 1e-12, "G3 quarter ends at y = 15");
  CHECK_NEAR(t[2], 1.0, 1e-12, "rise 2 from z = -1");
  CHECK_NEAR(m.length, hypot(5.0 * M_PI / 2, 2.0), 1e-12, "helix length");
  /* G2: normal -z, rise along the normal lowers z. */
  mv = make_arc(10.0, 10.0, -1.0, M_PI / 2, 2.0);
  swarf_motion_from_move(&mv, &m, NULL);
  swarf_motion_eval(&m, 1.0, t, NULL);
  CHECK_NEAR(t[1], 5.0, 1e-12, "G2 quarter ends at y = 5");
  CHECK_NEAR(t[2], -3.0, 1e-12, "G2 rise along -z");
}

static void test_velocity(void) {
  swarf_move mv = make_arc(0.0, 0.0, 1.0, 5.0, 3.0);
  swarf_motion m;
  double a = 0.37, h = 1e-6, tp[3], tm[3], td[3], v[3], w[3];
  swarf_motion_from_move(&mv, &m, NULL);
  swarf_motion_eval(&m, a + h, tp, NULL);
  swarf_motion_eval(&m, a - h, tm, NULL);
  swarf_motion_velocity(&m, a, td, v, w);
  for (int k = 0; k < 3; k++) {
    CHECK_NEAR(td[k], (tp[k] - tm[k]) / (2 * h), 1e-6, "tdot by central difference");
    CHECK(v[k] == td[k] && w[k] == 0.0, "xyz machine: v = tdot, omega = 0");
  }
}

static void test_bounds(void) {
  srand(7);
  for (int trial = 0; trial < 200; trial++) {
    double ang = 0.1 + 12.0 * rand() / RAND_MAX, rise = 20.0 * rand() / RAND_MAX - 10.0;
    double n[3] = {rand() - RAND_MAX / 2.0, rand() - RAND_MAX / 2.0, rand() - RAND_MAX / 2.0};
    double len = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    swarf_move mv = make_arc(1.0, 2.0, 1.0, ang, rise);
    swarf_motion m;
    double lo[3], hi[3], slo[3] = {1e9, 1e9, 1e9}, shi[3] = {-1e9, -1e9, -1e9}, t[3];
    for (int k = 0; k < 3; k++)
      mv.normal[k] = n[k] / len;
    swarf_motion_from_move(&mv, &m, NULL);
    swarf_motion_bounds(&m, lo, hi);
    for (int i = 0; i <= 20000; i++) {
      swarf_motion_eval(&m, i / 20000.0, t, NULL);
      for (int k = 0; k < 3; k++) {
        slo[k] = fmin(slo[k], t[k]);
        shi[k] = fmax(shi[k], t[k]);
      }
    }
    for (int k = 0; k < 3; k++) {
      CHECK(lo[k] <= slo[k] + 1e-9 && hi[k] >= shi[k] - 1e-9, "bounds contain the path");
      CHECK(slo[k] - lo[k] < 1e-4 && hi[k] - shi[k] < 1e-4,
            "bounds are tight (trial %d k %d: %g %g / %g %g)", trial, k, lo[k], slo[k], hi[k],
            shi[k]);
    }
  }
}

/* swarf_motion_pose_table: more motions than its slots (an array of them, as
 * a batch holds), each with more poses than its memory budget keeps for all,
 * asked for twice in two orders, and a motion changed in place, by contents
 * and by number (swarf_motion_pose_table_id), with rates
 * (swarf_motion_pose_table_rates): every table holds the motion's own poses
 * (swarf_motion_pose at i / n) and their rates. */
static int table_matches_id(const swarf_motion *m, int n, uint64_t id) {
  const swarf_pose *t;
  swarf_pose p;
  if (swarf_motion_pose_table_id(m, n, id, &t) != SWARF_OK) return 0;
  for (int i = 0; i <= n; i += n / 4) {
    swarf_motion_pose(m, (double)i / n, &p);
    if (memcmp(&p, &t[i], sizeof p) != 0) return 0;
  }
  return 1;
}

static int table_matches(const swarf_motion *m, int n) {
  return table_matches_id(m, n, 0);
}

/* The table with its rates (swarf_motion_pose_table_rates): the poses as
 * above, each rate that of its pose (swarf_pose_rates_of). */
static int rates_match(const swarf_motion *m, int n, uint64_t id) {
  const swarf_pose *t;
  const swarf_pose_rates *r;
  swarf_pose p;
  swarf_pose_rates q;
  if (swarf_motion_pose_table_rates(m, n, id, &t, &r) != SWARF_OK) return 0;
  for (int i = 0; i <= n; i += n / 4) {
    swarf_motion_pose(m, (double)i / n, &p);
    swarf_pose_rates_of(&p, &q);
    if (memcmp(&p, &t[i], sizeof p) != 0 || memcmp(&q, &r[i], sizeof q) != 0) return 0;
  }
  return 1;
}

static void test_pose_table(void) {
  enum { NM = 1100, N = 2000 };
  swarf_motion *ms = malloc(sizeof *ms * NM);
  int bad = 0;
  CHECK(ms != NULL, "memory");
  if (ms == NULL) return;
  for (int i = 0; i < NM; i++) {
    swarf_move mv = make_arc(0.01 * i, 0.0, 1.0, 0.5 + 1e-3 * i, 0.1);
    swarf_motion_from_move(&mv, &ms[i], NULL);
  }
  for (int i = 0; i < NM; i++)
    bad += !table_matches(&ms[i], N);
  for (int i = NM - 1; i >= 0; i--)
    bad += !table_matches(&ms[i], i % 2 ? N : 16);
  ms[7].p0[0] += 1.0; /* changed in place: recomputed */
  bad += !table_matches(&ms[7], N) + !table_matches(&ms[7], 16);
  /* by number (swarf_motion_pose_table_id), mixed with the comparison: a
   * table found by contents takes the number, a new number after a change */
  for (int i = 0; i < NM; i++)
    bad += !table_matches_id(&ms[i], 16, 1000 + i) + !table_matches(&ms[i], 16) +
           !table_matches_id(&ms[i], 16, 1000 + i);
  ms[9].p1[1] -= 2.0;
  bad += !table_matches_id(&ms[9], 16, 5000) + !table_matches(&ms[9], 16);
  ms[9].th1[0] += 0.5, ms[9].p1[1] += 1.0;
  bad += !table_matches(&ms[9], 16) + !table_matches_id(&ms[9], 16, 5001) +
         !table_matches_id(&ms[9], N, 5001);
  /* with rates, after refills by the other lookups (a table refilled has none) */
  for (int i = 0; i < NM; i += 3)
    bad += !rates_match(&ms[i], 16, 9000 + i) + !table_matches(&ms[i], N) +
           !rates_match(&ms[i], 16, 9000 + i) + !rates_match(&ms[i], N, 0);
  ms[11].th0[1] += 0.25;
  bad += !rates_match(&ms[11], N, 0) + !rates_match(&ms[11], N, 7777);
  CHECK(bad == 0, "pose tables match their motions (%d do not)", bad);
  free(ms);
}

int main(void) {
  test_line();
  test_helix_quarter();
  test_velocity();
  test_bounds();
  test_pose_table();
  return check_done();
}
