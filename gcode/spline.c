/* SPDX-License-Identifier: MPL-2.0 */
/* spline.c -- G5 (cubic) and G5.1 (quadratic) splines as short lines.
 *
 * LinuxCNC's G5 X Y I J P Q is the cubic Bezier from the current point P0
 * to P3 = (X, Y) with control points P1 = P0 + (I, J) and P2 = P3 + (P, Q);
 * I J may be left out after a G5 and are then -(P, Q) of the last one (a
 * smooth join; 0 when the last motion was no G5). G5.1 X Y I J is the
 * quadratic Bezier with control point P0 + (I, J). Both only in G17; the
 * other axes go straight from start to end along the curve's parameter.
 *
 * The simulator sweeps lines and arcs, so the curve goes out as straight
 * feeds at equal parameter steps, so many that no chord leaves the curve by
 * more than SWARF_GC_SPLINE_TOLERANCE: the chord of a parameter step h
 * deviates at most max|B''| h^2 / 8, and |B''| is largest at an end of
 * the curve (linear in t for a cubic, constant for a quadratic). The canon
 * prints one NURBS_FEED call per block, as rs274 does; the lines are not
 * printed.
 */
#include <math.h>
#include <string.h>

#include "gcode_private.h"

#define MAX_PIECES 4096

static double norm2(double x, double y) {
  return sqrt(x * x + y * y);
}

/* Point at t of the Bezier with `n` + 1 control points (n = 2 or 3). */
static void bezier(const double px[4], const double py[4], int n, double t, double *x, double *y) {
  double u = 1 - t;
  if (n == 3) {
    double a = u * u * u, b = 3 * u * u * t, c = 3 * u * t * t, d = t * t * t;
    *x = a * px[0] + b * px[1] + c * px[2] + d * px[3];
    *y = a * py[0] + b * py[1] + c * py[2] + d * py[3];
  } else {
    double a = u * u, b = 2 * u * t, c = t * t;
    *x = a * px[0] + b * px[1] + c * px[2];
    *y = a * py[0] + b * py[1] + c * py[2];
  }
}

/* Pieces so that every chord stays within the tolerance. */
static int pieces(const double px[4], const double py[4], int n) {
  double m;
  if (n == 3)
    m = 6 * fmax(norm2(px[2] - 2 * px[1] + px[0], py[2] - 2 * py[1] + py[0]),
                 norm2(px[3] - 2 * px[2] + px[1], py[3] - 2 * py[2] + py[1]));
  else
    m = 2 * norm2(px[2] - 2 * px[1] + px[0], py[2] - 2 * py[1] + py[0]);
  double k = ceil(sqrt(m / (8 * SWARF_GC_SPLINE_TOLERANCE)));
  return k < 1 ? 1 : k > MAX_PIECES ? MAX_PIECES : (int)k;
}

static int check(const swarf_gc_block *b, const swarf_gc_state *st, int cubic, swarf_error *f) {
  int col = b->motion_column;
  const char *name = cubic ? "G5" : "G5.1";
  if (st->modal.plane != 170) return SWARF_GC_FAIL(f, SWARF_GCODE_E_SPLINE_PLANE, col);
  if (cubic && (!swarf_gc_block_has(b, 'P') || !swarf_gc_block_has(b, 'Q')))
    return SWARF_GC_FAIL(f, SWARF_GCODE_E_SPLINE_PQ, col);
  if (!cubic && (!swarf_gc_block_has(b, 'I') || !swarf_gc_block_has(b, 'J')))
    return SWARF_GC_FAIL(f, SWARF_GCODE_E_SPLINE_IJ, col);
  if (st->modal.feed_mode == 930)
    return SWARF_GC_FAIL(f, SWARF_GCODE_E_SPLINE_MODE, col, name, "inverse time feed (G93)");
  if (swarf_gc_comp_active(st))
    return SWARF_GC_FAIL(f, SWARF_GCODE_E_SPLINE_MODE, col, name, "cutter radius compensation");
  if (st->feed <= 0) return SWARF_GC_FAIL(f, SWARF_GCODE_E_G1_ZERO_FEED, col);
  return SWARF_OK;
}

int swarf_gc_spline(const swarf_gc_block *b, swarf_gc_state *st, swarf_gc_exec *ex,
                    swarf_error *f) {
  int cubic = b->motion == 50, n = cubic ? 3 : 2, k, status = check(b, st, cubic, f);
  double s = swarf_gc_scale(st), end[SWARF_NAXES], start[SWARF_NAXES], px[4], py[4], ij[2];
  if (status != SWARF_OK) return status;
  swarf_gc_find_end(b, st, end);
  memcpy(start, st->pos, sizeof start);
  if (swarf_gc_block_has(b, 'I') || swarf_gc_block_has(b, 'J') || !cubic) {
    ij[0] = swarf_gc_block_word(b, 'I')->value * s;
    ij[1] = swarf_gc_block_word(b, 'J')->value * s;
  } else {
    ij[0] = st->spline_last ? -st->spline_pq[0] : 0;
    ij[1] = st->spline_last ? -st->spline_pq[1] : 0;
  }
  px[0] = start[0], py[0] = start[1];
  px[1] = start[0] + ij[0], py[1] = start[1] + ij[1];
  if (cubic) {
    st->spline_pq[0] = swarf_gc_block_word(b, 'P')->value * s;
    st->spline_pq[1] = swarf_gc_block_word(b, 'Q')->value * s;
    px[2] = end[0] + st->spline_pq[0], py[2] = end[1] + st->spline_pq[1];
  }
  px[n] = end[0], py[n] = end[1];
  swarf_gc_out_text(ex->out, "NURBS_FEED(%d, ...)", n + 1);
  k = pieces(px, py, n);
  for (int i = 1; i <= k; i++) {
    double t = (double)i / k, p[SWARF_NAXES];
    size_t before = ex->out->count;
    for (int a = 2; a < SWARF_NAXES; a++)
      p[a] = start[a] + t * (end[a] - start[a]);
    bezier(px, py, n, t, &p[0], &p[1]);
    if (i == k) memcpy(p, end, sizeof p);
    swarf_gc_out_straight(ex->out, st, SWARF_GC_CALL_FEED, p, b->motion_column);
    if (ex->out->count > before) ex->out->calls[ex->out->count - 1].print = SWARF_GC_PRINT_NONE;
    memcpy(st->pos, p, sizeof st->pos);
  }
  return SWARF_OK;
}
