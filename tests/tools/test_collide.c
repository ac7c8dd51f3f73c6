/* SPDX-License-Identifier: MPL-2.0 */
/* test_collide.c -- collisions of shanks, holders and fixtures, end to end
 * through the driver (G-code text -> motions -> sweeps -> stock), with the
 * alarm callback.
 *
 * Every case has a geometry whose depth is known in closed form (written
 * next to it): the lift along the tool axis that clears the part, e.g. a
 * holder face 2 mm below a flat top face is 2.0 mm deep. The reported depth
 * must match to 0.02 mm (the bisection runs to voxel/8 = 0.025 mm and the
 * midpoint is reported; faces parallel to the stock's exact-distance faces),
 * the line and the kind exactly, and no
 * other alarm may be raised: plunges and slots within the flute length, a
 * shank as wide as the cutter following it into its own hole, and a tool
 * working beside a fixture raise nothing. Shank and holder never cut: the
 * removed volume of a run with a holder is that of the run without.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "swarf_sim.h"

#define VOXEL 0.2

static long depth_limit; /* cfg.collision_depths of the next run */

typedef struct {
  swarf_alarm a[64];
  int n;
} alarms;

static void on_alarm(void *user, const swarf_alarm *a) {
  alarms *l = user;
  if (l->n < 64) l->a[l->n++] = *a;
}

typedef struct {
  swarf_alarm_kind kind;
  long line;
  double depth; /* analytic, mm */
  int index, part;
  double tol; /* mm; 0: 0.02 */
} expect;

static const char *kind_name(swarf_alarm_kind k) {
  static const char *n[] = {"rapid", "shank", "holder", "fixture", "gouge"};
  return (unsigned)k < 5 ? n[k] : "?";
}

/* Runs `program` with the tools (specs) and fixtures given; checks that the
 * alarms are exactly `want`. Returns the removed volume. */
static double run(const char *name, const char *program, const char *const *tools,
                  const char *const *holders, const char *const *fixtures, const expect *want,
                  int nwant) {
  swarf_sim_config cfg;
  swarf_error err;
  alarms got = {0};
  swarf_sim_config_init(&cfg);
  cfg.voxel = VOXEL;
  cfg.collision_depths = depth_limit;
  CHECK(swarf_sim_parse_stock("box:0,0,-40,60,40,0", &cfg.stock, &err) == SWARF_OK, "stock");
  for (int i = 0; tools[i] != NULL; i++) {
    swarf_sim_tool t;
    CHECK(swarf_sim_parse_tool(tools[i], &t, &err) == SWARF_OK, "%s: %s", tools[i], err.message);
    CHECK(swarf_sim_config_put_tool(&cfg, &t, &err) == SWARF_OK, "%s: %s", tools[i], err.message);
  }
  for (int i = 0; holders && holders[i] != NULL; i++) {
    swarf_sim_tool t;
    CHECK(swarf_sim_parse_holder(holders[i], &t, &err) == SWARF_OK, "%s: %s", holders[i],
          err.message);
    CHECK(swarf_sim_config_put_holder(&cfg, &t, &err) == SWARF_OK, "%s", err.message);
  }
  for (int i = 0; fixtures && fixtures[i] != NULL; i++)
    CHECK(swarf_sim_parse_fixture(fixtures[i], &cfg.fixtures[cfg.nfixtures++], &err) == SWARF_OK,
          "%s: %s", fixtures[i], err.message);
  cfg.cb.alarm = on_alarm;
  cfg.cb.user = &got;
  swarf_stock *out = NULL;
  swarf_sim_report rep;
  swarf_status s = swarf_sim_run_text(&cfg, name, program, strlen(program), &out, &rep, &err);
  CHECK(s == SWARF_OK, "%s: %s", name, err.message);
  CHECK(got.n == nwant, "%s: %d alarms, expected %d", name, got.n, nwant);
  for (int i = 0; i < got.n; i++)
    printf("%s:%ld: %s of T%d, fixture %d, part %d, %.4f mm deep at (%.2f, %.2f, %.2f)\n", name,
           got.a[i].line, kind_name(got.a[i].kind), got.a[i].tool, got.a[i].index, got.a[i].part,
           got.a[i].depth, got.a[i].at[0], got.a[i].at[1], got.a[i].at[2]);
  for (int i = 0; i < nwant && i < got.n; i++) {
    const swarf_alarm *a = &got.a[i];
    CHECK(a->kind == want[i].kind && a->line == want[i].line && a->index == want[i].index &&
              a->part == want[i].part,
          "%s: alarm %d: %s line %ld fixture %d part %d, expected %s line %ld fixture %d part %d",
          name, i + 1, kind_name(a->kind), a->line, a->index, a->part, kind_name(want[i].kind),
          want[i].line, want[i].index, want[i].part);
    const double tol = want[i].tol > 0 ? want[i].tol : 0.02;
    if (isnan(want[i].depth))
      CHECK(isnan(a->depth), "%s: alarm %d: depth not measured", name, i + 1);
    else
      CHECK(fabs(a->depth - want[i].depth) <= tol, "%s: alarm %d: %.4f mm deep, expected %.4f",
            name, i + 1, a->depth, want[i].depth);
  }
  long coll = rep.alarm_count[SWARF_ALARM_SHANK] + rep.alarm_count[SWARF_ALARM_HOLDER] +
              rep.alarm_count[SWARF_ALARM_FIXTURE];
  CHECK(rep.collisions == coll && rep.alarms >= coll, "%s: report counts %ld collisions of %ld",
        name, rep.collisions, coll);
  double removed = rep.volume_before - rep.volume_after;
  swarf_stock_free(out);
  return removed;
}

int main(void) {
  /* T1: flat D6, flutes 10, stick-out 25 (shank D6 from 10 to 25), holder D20 x 40. */
  static const char *t1[] = {"T1=flat,D6,L10,S25", NULL};
  static const char *h1[] = {"T1=20x40", NULL};

  /* 1. Holder plunge: the tip to -27 puts the holder face (tip + 25) at -2:
   * 2 mm deep. The shank (as wide as the flutes) follows them into their
   * hole: no shank alarm. The holder never cut the ring it entered, so the
   * retract (line 4) starts inside it: 2 mm again. */
  const expect e1[] = {{SWARF_ALARM_HOLDER, 3, 2.0, 0, 2, 0},
                       {SWARF_ALARM_HOLDER, 4, 2.0, 0, 2, 0}};
  run("holder-plunge.ngc", "G0 X20 Y20 Z5\nG1 Z-20 F300\nG1 Z-27\nG0 Z30\nM2\n", t1, h1, NULL, e1,
      2);

  /* The same with depths measured for the first collision of each kind only. */
  const expect e1n[] = {{SWARF_ALARM_HOLDER, 3, 2.0, 0, 2, 0},
                        {SWARF_ALARM_HOLDER, 4, NAN, 0, 2, 0}};
  depth_limit = 1;
  run("holder-plunge-1.ngc", "G0 X20 Y20 Z5\nG1 Z-20 F300\nG1 Z-27\nG0 Z30\nM2\n", t1, h1, NULL,
      e1n, 2);
  depth_limit = 0;

  /* 2. Shank in a lateral move deeper than the flutes: the tip at -13
   * leaves the shank's bottom face at -3 under the top face in uncut
   * material: 3 mm deep (line 4). The plunge (line 3) is clean, and so is
   * the retract (line 5, a feed: the flutes cut the roof over the slot and
   * the shank follows them). */
  const expect e2[] = {{SWARF_ALARM_SHANK, 4, 3.0, 0, 1, 0}};
  run("shank-slot.ngc", "G0 X10 Y20 Z5\nG0 Z1\nG1 Z-13 F300\nG1 X40\nG1 Z30\nM2\n", t1, h1, NULL,
      e2, 1);

  /* 3. A shank wider than the cutter (N8 on a D4): a plunge to -12 with
   * flutes of 8 brings the shank's ring (r 2..4) 4 mm under the top (line
   * 4; the retract, line 5, too); a second plunge, in a pocket already
   * cleared 20 mm deep by a D10 flat (T3), raises nothing. */
  static const char *t3[] = {"T2=flat,D4,L8,S40,N8", "T3=flat,D10,L30", NULL};
  const expect e3[] = {{SWARF_ALARM_SHANK, 4, 4.0, 0, 1, 0}, {SWARF_ALARM_SHANK, 5, 4.0, 0, 1, 0}};
  run("shank-ring.ngc",
      "T2 M6\nG0 X15 Y20 Z5\nG1 Z0 F300\nG1 Z-12\nG0 Z50\n"
      "T3 M6\nG0 X40 Y20 Z5\nG1 Z-20\nG0 Z50\n"
      "T2 M6\nG0 X40 Y20 Z5\nG1 Z-12\nG0 Z50\nM2\n",
      t3, NULL, NULL, e3, 2);

  /* 4. Within the flute length: plunges to -9.5 and slots at -9 with
   * flutes of 10, the holder far above: nothing. */
  const expect none[1] = {{0, 0, 0, 0, 0, 0}};
  double with = run("within-flutes.ngc",
                    "G0 X10 Y10 Z5\nG1 Z-9.5 F300\nG1 X50\nG1 Y30\nG1 X10 Z-9\nG0 Z5\n"
                    "G0 X30 Y20\nG1 Z-9.9\nG0 Z30\nM2\n",
                    t1, h1, NULL, none, 0);
  static const char *bare[] = {"T1=flat,D6,L10", NULL};
  double without = run("within-flutes-bare.ngc",
                       "G0 X10 Y10 Z5\nG1 Z-9.5 F300\nG1 X50\nG1 Y30\nG1 X10 Z-9\nG0 Z5\n"
                       "G0 X30 Y20\nG1 Z-9.9\nG0 Z30\nM2\n",
                       bare, NULL, NULL, none, 0);
  CHECK(fabs(with - without) < 1e-9, "shank and holder never cut: removed %.6f vs %.6f mm^3", with,
        without);

  /* 5. Fixtures: a clamp on the top face at x 50..60 (fixture 1), a vice
   * jaw beside the stock at y -10..-4 (fixture 2) and a tall clamp at x 0..8,
   * y 30..40, top 16 (fixture 3). A traverse at Z2 runs the cutter (2..12)
   * into the clamp (top 5): 3 mm, and the retract from there again (lines 2
   * and 3); a plunge at (4, 25) to Z-10 brings the holder's face (Z15, radius
   * 10) 1 mm below the tall clamp's top (line 5, and the retract, line 6); a
   * cut along the jaw 1 mm away raises nothing. */
  static const char *fx[] = {"box:50,0,0,60,40,5", "box:0,-10,-30,60,-4,5", "box:0,30,0,8,40,16",
                             NULL};
  const expect e5[] = {{SWARF_ALARM_FIXTURE, 2, 3.0, 1, 0, 0},
                       {SWARF_ALARM_FIXTURE, 3, 3.0, 1, 0, 0},
                       {SWARF_ALARM_FIXTURE, 5, 1.0, 3, 2, 0},
                       {SWARF_ALARM_FIXTURE, 6, 1.0, 3, 2, 0}};
  run("fixtures.ngc",
      "G0 X30 Y20 Z2\nG1 X58 F500\nG0 Z30\nG0 X4 Y25\nG1 Z-10\nG0 Z40\n"
      "G0 X20 Y0 Z5\nG1 Z-1\nG1 X45\nG0 Z40\nM2\n",
      t1, h1, fx, e5, 4);
  /* 6. A cone in the holder: T1's holder is a D20 x 10 cylinder under a cone
   * from D20 to D40 over 10 mm (radius = 10 + height above its base). T3
   * (flat D24, flutes 40) clears a pocket of radius 12 to Z-30; T1 plunged
   * there to Z-39 has its cylinder (Z-14..-4) free in the pocket and its cone
   * from Z-4 reaching radius 14 at the pocket's rim (Z0, radius 12): lifted 2
   * mm, the cone's radius at Z0 is 12. The overlap is a wedge at the rim, not
   * two parallel faces, so the depth is good to about half a voxel. */
  static const char *t6[] = {"T1=flat,D6,L10,S25", "T3=flat,D24,L40", NULL};
  static const char *h6[] = {"T1=20x10,20-40x10", NULL};
  const expect e6[] = {{SWARF_ALARM_HOLDER, 8, 2.0, 0, 2, 0.12},
                       {SWARF_ALARM_HOLDER, 9, 2.0, 0, 2, 0.12}};
  run("holder-cone.ngc",
      "T3 M6\nG0 X30 Y20 Z5\nG1 Z-30 F300\nG0 Z50\n"
      "T1 M6\nG0 X30 Y20 Z5\nG1 Z-30\nG1 Z-39\nG0 Z50\nM2\n",
      t6, h6, NULL, e6, 2);
  return check_done();
}
