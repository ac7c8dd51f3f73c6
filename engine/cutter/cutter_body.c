/* SPDX-License-Identifier: MPL-2.0 */
/* cutter_body.c -- bodies of revolution piece by piece (engine.h): hulls of
 * circles, frustums and QSS pieces, validated, with the cutter's bounds.
 *
 * A piece is added complete (its outline traced, its extent known) or not
 * at all; finish sets diameter, zmin, length and convex. Every function
 * takes caller-owned values and keeps no state.
 */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "engine_private.h"

void swarf_cutter_begin(swarf_cutter *c) {
  if (c == NULL) return;
  memset(c, 0, sizeof *c);
  c->shape = SWARF_CUTTER_BODY;
  for (int i = 0; i < 8; i++)
    c->param[i] = NAN;
}

static swarf_profile_piece *new_piece(swarf_cutter *c, swarf_error *err) {
  swarf_profile_piece *pc;
  if (c->npieces == SWARF_CUTTER_MAX_PIECES) {
    swarf_error_set(err, SWARF_ERR_TOOL, "a body of revolution has at most %d pieces",
                    SWARF_CUTTER_MAX_PIECES);
    return NULL;
  }
  pc = &c->piece[c->npieces];
  memset(pc, 0, sizeof *pc);
  return pc;
}

/* Clip the upper chain (and the side) at height top, adding a flat top face. */
static int clip_top(swarf_profile_piece *pc, double top) {
  swarf_profile_elem *s = &pc->el[pc->side], *e;
  double cut[2] = {0.0, top}, axis[2] = {0.0, top};
  int i;
  if (!(top < pc->zhi)) return 0;
  if (top < s->z0) return -1;
  if (top <= s->z1) {
    s->z1 = top;
    s->inv = s->z1 > s->z0 ? 1.0 / ((s->z1 - s->z0) * (s->z1 - s->z0)) : 0.0;
    pc->nel = pc->side + 1;
    cut[0] = s->r0;
  } else {
    for (i = pc->side + 1; i < pc->nel; i++)
      if (fmax(pc->el[i].z0, pc->el[i].z1) >= top) break;
    if (i == pc->nel) return 0;
    e = &pc->el[i];
    if (e->rad > 0.0) {
      double d = e->rad * e->rad - (top - e->cz) * (top - e->cz);
      cut[0] = e->cr + (d > 0.0 ? sqrt(d) : 0.0);
    } else {
      cut[0] = e->z1 != e->z0 ? e->r0 + (top - e->z0) / (e->z1 - e->z0) * (e->r1 - e->r0) : e->r0;
    }
    e->r1 = cut[0], e->z1 = top;
    if (e->rad == 0.0) {
      double l2 = (e->r1 - e->r0) * (e->r1 - e->r0) + (e->z1 - e->z0) * (e->z1 - e->z0);
      e->inv = l2 > 0.0 ? 1.0 / l2 : 0.0;
    }
    pc->nel = i + 1;
  }
  if (cut[0] > 0.0) {
    if (pc->nel == SWARF_PIECE_MAX_ELEMS) return -1;
    e = &pc->el[pc->nel++];
    memset(e, 0, sizeof *e);
    e->r0 = cut[0], e->z0 = top, e->r1 = axis[0], e->z1 = axis[1];
    e->inv = 1.0 / (cut[0] * cut[0]);
  }
  pc->zhi = top;
  return 0;
}

swarf_status swarf_cutter_add_hull_clipped(swarf_cutter *c, const double (*circles)[3], int n,
                                           double top, swarf_error *err) {
  swarf_profile_piece *pc;
  double reach = 0.0;
  if (c == NULL || circles == NULL)
    return swarf_error_set(err, SWARF_ERR_ARG, "no body or circles");
  if (n < 1 || n > SWARF_PIECE_MAX_CIRCLES)
    return swarf_error_set(err, SWARF_ERR_TOOL, "a hull piece takes 1 to %d circles (got %d)",
                           SWARF_PIECE_MAX_CIRCLES, n);
  for (int i = 0; i < n; i++) {
    const double *k = circles[i];
    if (!isfinite(k[0]) || !isfinite(k[1]) || !isfinite(k[2]) || k[0] < 0.0 || k[2] < 0.0)
      return swarf_error_set(err, SWARF_ERR_TOOL,
                             "circle %d of a hull piece needs finite r >= 0, z, radius >= 0",
                             i + 1);
    reach = fmax(reach, k[0] + k[2]);
  }
  if (!(reach > 0.0))
    return swarf_error_set(err, SWARF_ERR_TOOL,
                           "a hull piece has no width (every circle on the axis "
                           "with radius 0)");
  if ((pc = new_piece(c, err)) == NULL) return SWARF_ERR_TOOL;
  pc->kind = SWARF_PIECE_HULL;
  pc->convex = 1;
  pc->ncircle = n;
  memcpy(pc->circle, circles, sizeof(double[3]) * (size_t)n);
  if (swarf_profile_hull_build(pc) != 0)
    return swarf_error_set(err, SWARF_ERR_TOOL, "the outline of a hull piece has too many parts");
  swarf_profile_hull_extent(pc);
  if (isfinite(top) && clip_top(pc, top) != 0)
    return swarf_error_set(err, SWARF_ERR_TOOL, "a hull piece cannot be cut below its widest part");
  c->npieces++;
  return SWARF_OK;
}

swarf_status swarf_cutter_add_hull(swarf_cutter *c, const double (*circles)[3], int n,
                                   swarf_error *err) {
  return swarf_cutter_add_hull_clipped(c, circles, n, INFINITY, err);
}

swarf_status swarf_cutter_add_frustum(swarf_cutter *c, double z0, double r0, double z1, double r1,
                                      swarf_error *err) {
  const double k[2][3] = {{r0, z0, 0.0}, {r1, z1, 0.0}};
  if (!isfinite(z0) || !isfinite(z1) || !(z0 < z1))
    return swarf_error_set(err, SWARF_ERR_TOOL, "a frustum needs heights z0 < z1 (got %g, %g)", z0,
                           z1);
  if (!isfinite(r0) || !isfinite(r1) || r0 < 0.0 || r1 < 0.0 || !(r0 + r1 > 0.0))
    return swarf_error_set(err, SWARF_ERR_TOOL,
                           "a frustum needs radii >= 0, not both 0 (got %g, %g)", r0, r1);
  return swarf_cutter_add_hull(c, k, 2, err);
}

/* ---- QSS pieces ------------------------------------------------------------ */

static void qss_curve(const swarf_profile_piece *pc, double s, double y[2]) {
  double c2 = 1.0 - s * s;
  y[0] = sqrt(c2 > 0.0 ? c2 : 0.0) * (pc->q0 - pc->q2 * s * s);
  y[1] = (-pc->q2 * s * s + pc->q0 + 2.0 * pc->q2) * s + pc->q1 + pc->lift;
}

/* Proper crossing of segments ab and cd (strict: shared ends do not count). */
static int seg_cross(const double a[2], const double b[2], const double c[2], const double d[2]) {
  double d1 = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
  double d2 = (b[0] - a[0]) * (d[1] - a[1]) - (b[1] - a[1]) * (d[0] - a[0]);
  double d3 = (d[0] - c[0]) * (a[1] - c[1]) - (d[1] - c[1]) * (a[0] - c[0]);
  double d4 = (d[0] - c[0]) * (b[1] - c[1]) - (d[1] - c[1]) * (b[0] - c[0]);
  return ((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0)) && ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0));
}

/* The profile curve must not cross itself (the region would not be one). */
#define QSS_SAMPLES 240
static int qss_simple(const swarf_profile_piece *pc) {
  double y[QSS_SAMPLES + 1][2];
  for (int i = 0; i <= QSS_SAMPLES; i++)
    qss_curve(pc, -cos(3.14159265358979323846 * i / QSS_SAMPLES), y[i]);
  for (int i = 0; i < QSS_SAMPLES; i++)
    for (int j = i + 2; j < QSS_SAMPLES; j++)
      if (seg_cross(y[i], y[i + 1], y[j], y[j + 1])) return 0;
  return 1;
}

swarf_status swarf_cutter_add_qss(swarf_cutter *c, const swarf_qss *q, double lift,
                                  swarf_error *err) {
  swarf_profile_piece *pc;
  double ends[5], lo = INFINITY, hi = -INFINITY, rmax = 0.0, cusp;
  int ne = 0;
  if (c == NULL || q == NULL) return swarf_error_set(err, SWARF_ERR_ARG, "no body or QSS");
  if (!isfinite(q->a) || !isfinite(q->b) || !isfinite(q->e) || !isfinite(q->f) || !isfinite(lift))
    return swarf_error_set(err, SWARF_ERR_TOOL, "the QSS coefficients must be finite numbers");
  if ((pc = new_piece(c, err)) == NULL) return SWARF_ERR_TOOL;
  pc->kind = SWARF_PIECE_QSS;
  pc->qss = *q;
  pc->q2 = q->b - q->a, pc->q1 = q->e, pc->q0 = q->a + q->f, pc->lift = lift;
  if (!(pc->q0 > 0.0) || !(pc->q0 - pc->q2 > 0.0))
    return swarf_error_set(err, SWARF_ERR_TOOL,
                           "the QSS profile crosses its axis: need a + f > 0 (got %g) and "
                           "2a - b + f > 0 (got %g)",
                           pc->q0, pc->q0 - pc->q2);
  if (!qss_simple(pc))
    return swarf_error_set(err, SWARF_ERR_TOOL,
                           "the QSS profile crosses itself: it bounds no solid");
  ends[ne++] = -1.0, ends[ne++] = 1.0, ends[ne++] = 0.0;
  if (pc->q2 != 0.0 && (cusp = (pc->q0 + 2.0 * pc->q2) / (3.0 * pc->q2)) > 0.0 && cusp < 1.0)
    ends[ne++] = sqrt(cusp), ends[ne++] = -sqrt(cusp);
  for (int i = 0; i < ne; i++) {
    double y[2];
    qss_curve(pc, ends[i], y);
    lo = fmin(lo, y[1]), hi = fmax(hi, y[1]), rmax = fmax(rmax, y[0]);
  }
  rmax = fmax(rmax, pc->q0);
  pc->convex = pc->q0 + 2.0 * pc->q2 >= 0.0;
  pc->zlo = lo, pc->zhi = hi, pc->rmax = rmax;
  pc->zw0 = pc->zw1 = pc->q1 + lift;
  c->npieces++;
  return SWARF_OK;
}

swarf_status swarf_cutter_finish(swarf_cutter *c, swarf_error *err) {
  double rmax = 0.0, zlo = INFINITY, zhi = -INFINITY;
  if (c == NULL) return swarf_error_set(err, SWARF_ERR_ARG, "no body");
  if (c->npieces == 0)
    return swarf_error_set(err, SWARF_ERR_TOOL, "a body needs at least one piece");
  for (int i = 0; i < c->npieces; i++) {
    rmax = fmax(rmax, c->piece[i].rmax);
    zlo = fmin(zlo, c->piece[i].zlo);
    zhi = fmax(zhi, c->piece[i].zhi);
  }
  c->diameter = 2.0 * rmax;
  c->zmin = zlo;
  c->length = zhi;
  c->convex = c->npieces == 1 && c->piece[0].convex;
  return SWARF_OK;
}
