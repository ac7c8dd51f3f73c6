/* SPDX-License-Identifier: MPL-2.0 */
/* test_arcs.c -- G2/G3 in the three planes, centre and radius formats, both
 * signs of R, helices, P turns, G90.1, G91, G20, full circles.
 *
 * Each case gives the expected centre, normal, sweep and the point half way,
 * worked out by hand (see the comments), and the arc is evaluated here with
 * Rodrigues' formula, independently of the front end: p(1) must be the
 * programmed end and p(0.5) the expected middle, which pins the sense.
 */
#include <stdio.h>

#include "check.h"
#include "collect.h"

#define PI 3.14159265358979323846
#define R2 7.0710678118654752 /* 10 / sqrt(2) */

typedef struct {
  const char *name;
  const char *program; /* the arc is the last move */
  double end[3], center[3], normal[3], angle, rise;
  double mid[3];  /* p(0.5) */
  double end_tol; /* how far p(1) may be from the end (a spiral in tolerance) */
} arc_case;

/* clang-format off */
static const arc_case cases[] = {
    /* Start at angle 0 on the circle of radius 10 about the origin. */
    {"G17 G3 IJ quarter", "G0 X10\nG3 X0 Y10 I-10 J0 F100\n", {0, 10, 0}, {0, 0, 0}, {0, 0, 1},
     PI / 2, 0, {R2, R2, 0}, 0},
    {"G17 G2 IJ three quarters (J omitted)", "G0 X10\nG2 X0 Y10 I-10 F100\n", {0, 10, 0},
     {0, 0, 0}, {0, 0, -1}, 3 * PI / 2, 0, {-R2, -R2, 0}, 0},
    /* From the origin to (10,10) with |R| = 10: centres (10,0) and (0,10). */
    {"G2 R+ (short, centre (10,0))", "G2 X10 Y10 R10 F100\n", {10, 10, 0}, {10, 0, 0},
     {0, 0, -1}, PI / 2, 0, {10 - R2, R2, 0}, 0},
    {"G2 R- (long, centre (0,10))", "G2 X10 Y10 R-10 F100\n", {10, 10, 0}, {0, 10, 0},
     {0, 0, -1}, 3 * PI / 2, 0, {-R2, 10 + R2, 0}, 0},
    {"G3 R+ (short, centre (0,10))", "G3 X10 Y10 R10 F100\n", {10, 10, 0}, {0, 10, 0},
     {0, 0, 1}, PI / 2, 0, {R2, 10 - R2, 0}, 0},
    {"G3 R- (long, centre (10,0))", "G3 X10 Y10 R-10 F100\n", {10, 10, 0}, {10, 0, 0},
     {0, 0, 1}, 3 * PI / 2, 0, {10 + R2, -R2, 0}, 0},
    /* G18: first axis Z, second X; G2 turns about -Y (clockwise seen from +Y). */
    {"G18 G2 IK", "G0 X10\nG18 G2 X0 Z10 I-10 K0 F100\n", {0, 0, 10}, {0, 0, 0}, {0, -1, 0},
     PI / 2, 0, {R2, 0, R2}, 0},
    {"G18 G3 IK", "G0 X10\nG18 G3 X0 Z10 I-10 K0 F100\n", {0, 0, 10}, {0, 0, 0}, {0, 1, 0},
     3 * PI / 2, 0, {-R2, 0, -R2}, 0},
    {"G18 G2 R", "G0 X10\nG18 G2 X0 Z10 R10 F100\n", {0, 0, 10}, {0, 0, 0}, {0, -1, 0},
     PI / 2, 0, {R2, 0, R2}, 0},
    /* G19: first axis Y, second Z; G3 turns about +X. */
    {"G19 G3 JK", "G0 Y10\nG19 G3 Y0 Z10 J-10 K0 F100\n", {0, 0, 10}, {0, 0, 0}, {1, 0, 0},
     PI / 2, 0, {0, R2, R2}, 0},
    {"G19 G2 JK", "G0 Y10\nG19 G2 Y0 Z10 J-10 F100\n", {0, 0, 10}, {0, 0, 0}, {-1, 0, 0},
     3 * PI / 2, 0, {0, -R2, -R2}, 0},
    {"G19 G3 R", "G0 Y10\nG19 G3 Y0 Z10 R10 F100\n", {0, 0, 10}, {0, 0, 0}, {1, 0, 0}, PI / 2, 0,
     {0, R2, R2}, 0},
    /* Helices: rise is the displacement along the normal. */
    {"G17 G3 helix down", "G0 X10\nG3 X0 Y10 Z-5 I-10 F100\n", {0, 10, -5}, {0, 0, 0}, {0, 0, 1},
     PI / 2, -5, {R2, R2, -2.5}, 0},
    {"G17 G2 helix down", "G0 X10\nG2 X0 Y10 Z-5 I-10 F100\n", {0, 10, -5}, {0, 0, 0},
     {0, 0, -1}, 3 * PI / 2, 5, {-R2, -R2, -2.5}, 0},
    {"G18 G2 helix along Y", "G0 X10\nG18 G2 X0 Z10 Y3 I-10 F100\n", {0, 3, 10}, {0, 0, 0},
     {0, -1, 0}, PI / 2, -3, {R2, 1.5, R2}, 0},
    {"G17 G2 R helix", "G2 X10 Y10 Z2 R10 F100\n", {10, 10, 2}, {10, 0, 0}, {0, 0, -1}, PI / 2,
     -2, {10 - R2, R2, 1}, 0},
    /* Turns. */
    {"P3 full circles", "G0 X10\nG3 X10 Y0 I-10 P3 F100\n", {10, 0, 0}, {0, 0, 0}, {0, 0, 1},
     6 * PI, 0, {-10, 0, 0}, 0},
    {"P2 on a three-quarter arc", "G0 X10\nG2 X0 Y10 I-10 P2 F100\n", {0, 10, 0}, {0, 0, 0},
     {0, 0, -1}, 3 * PI / 2 + 2 * PI, 0, {R2, R2, 0}, 0},
    {"full circle, no end given", "G0 X10\nG2 I-5 F100\n", {10, 0, 0}, {5, 0, 0}, {0, 0, -1},
     2 * PI, 0, {0, 0, 0}, 0},
    /* Centre and distance modes, units. */
    {"G90.1 absolute centre", "G0 X10 Y5\nG90.1 G3 X0 Y15 I0 J5 F100\n", {0, 15, 0}, {0, 5, 0},
     {0, 0, 1}, PI / 2, 0, {R2, 5 + R2, 0}, 0},
    {"G91 arc", "G0 X10\nG91 G3 X-10 Y10 I-10 F100\n", {0, 10, 0}, {0, 0, 0}, {0, 0, 1}, PI / 2,
     0, {R2, R2, 0}, 0},
    {"G20 arc", "G20 G0 X1\nG3 X0 Y1 I-1 F10\n", {0, 25.4, 0}, {0, 0, 0}, {0, 0, 1}, PI / 2, 0,
     {25.4 / 1.4142135623730951, 25.4 / 1.4142135623730951, 0}, 0},
    {"modal arc with I alone", "G0 X10\nG2 X0 Y10 I-10 F100\nI-5\n", {0, 10, 0}, {-5, 10, 0},
     {0, 0, -1}, 2 * PI, 0, {-10, 10, 0}, 0},
    /* Start and end 1e-9 apart: a full circle (LinuxCNC's planner, 1e-8). */
    {"full circle with rounding noise", "G0 X10\nG2 X10 Y0.000000001 I-10 F100\n",
     {10, 1e-9, 0}, {0, 0, 0}, {0, 0, -1}, 2 * PI, 0, {-10, 0, 0}, 1e-8},
    /* A 1 micron arc of radius 1000 stays a 1e-6 rad arc, not a full circle. */
    {"tiny arc on a large radius", "G0 X1000\nG3 X999.9999999995 Y0.001 I-1000 F100\n",
     {999.9999999995, 0.001, 0}, {0, 0, 0}, {0, 0, 1}, 1e-6, 0,
     {999.999999999875, 0.0005, 0}, 1e-9},
    /* r1 = 5, r2 = 5.02: within 0.02*sqrt(2) mm; the move ends 0.02 short. */
    {"spiral within tolerance", "G2 X10.02 I5 F100\n", {10.02, 0, 0}, {5, 0, 0}, {0, 0, -1}, PI,
     0, {5, 5, 0}, 0.0201},
};
/* clang-format on */

static collected result;

static void check_case(const arc_case *k) {
  collected *c = run_text(k->program, &result);
  const swarf_move *mv;
  double p[3];
  CHECK(c->status == 0 && c->n > 0, "%s: status %d (%s)", k->name, c->status, c->error.message);
  if (c->status != 0 || c->n == 0) return;
  mv = &c->moves[c->n - 1];
  CHECK(mv->kind == SWARF_MOVE_ARC, "%s: not an arc", k->name);
  for (int i = 0; i < 3; i++) {
    CHECK_NEAR(mv->end[i], k->end[i], 1e-12, k->name);
    CHECK_NEAR(mv->center[i], k->center[i], 1e-9, k->name);
    CHECK_NEAR(mv->normal[i], k->normal[i], 0, k->name);
  }
  CHECK_NEAR(mv->angle, k->angle, 1e-9, k->name);
  CHECK_NEAR(mv->rise, k->rise, 1e-12, k->name);
  arc_point(mv, 0, p);
  for (int i = 0; i < 3; i++)
    CHECK_NEAR(p[i], mv->start[i], 1e-9, k->name);
  arc_point(mv, 1, p);
  for (int i = 0; i < 3; i++)
    CHECK_NEAR(p[i], mv->end[i], k->end_tol + 1e-9, k->name);
  arc_point(mv, 0.5, p);
  for (int i = 0; i < 3; i++)
    CHECK_NEAR(p[i], k->mid[i], 1e-7, k->name);
  CHECK(mv->feed > 0, "%s: feed", k->name);
}

int main(void) {
  for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++)
    check_case(&cases[i]);
  return check_done();
}
