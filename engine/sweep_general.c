/* sweep_general.c -- swept volumes of a non-convex QSS piece under any
 * motion (placeholder: the rigid search; replaced by the certified chord
 * bound). */
#include <math.h>

#include "engine_private.h"

static double piece_body(const void *ctx, const double q[3], double grad[3]) {
  return swarf_profile_piece_sdf_grad((const swarf_profile_piece *)ctx, q, grad);
}

double swarf_sweep_general_sdf(const swarf_sweep *s, const double p[3], double *alpha) {
  const swarf_cutter *c = s->cutter;
  double best = INFINITY, ab = 0.0;
  for (int i = 0; i < c->npieces; i++) {
    double a = 0.0, g = swarf_sweep_rigid_body_below(s, piece_body, &c->piece[i], p, best, &a);
    if (g < best) best = g, ab = a;
  }
  if (alpha != NULL) *alpha = ab;
  return best;
}
