/* SPDX-License-Identifier: MPL-2.0 */
/* exact_motion.c -- rational rigid motions: rotation by alpha about an axis
 * through the origin (rational direction w with rational length) at unit
 * angular speed, and t(alpha) = alpha tdot, evaluated exactly at rational
 * B = tan(alpha / 2) (sin alpha = 2B/(1+B^2), cos alpha = (1-B^2)/(1+B^2)).
 *
 * U = cos I + sin [k]x + (1 - cos) k k^T with k = w / |w|; the angular
 * velocity in the moving frame is U^T k = k, and v = U^T tdot (eq. 7).
 * A swarf_xmotion owns its rationals (init/clear).
 */
#include "envelope_exact.h"

void swarf_xmotion_init(swarf_xmotion *m) {
  for (int i = 0; i < 9; i++)
    fmpq_init(m->U + i);
  for (int i = 0; i < 3; i++) {
    fmpq_init(m->v + i);
    fmpq_init(m->omega + i);
    fmpq_init(m->tdot + i);
  }
  fmpq_init(m->B);
}

void swarf_xmotion_clear(swarf_xmotion *m) {
  for (int i = 0; i < 9; i++)
    fmpq_clear(m->U + i);
  for (int i = 0; i < 3; i++) {
    fmpq_clear(m->v + i);
    fmpq_clear(m->omega + i);
    fmpq_clear(m->tdot + i);
  }
  fmpq_clear(m->B);
}

/* |w| when it is rational (0 otherwise, also for w = 0). */
static int axis_length(fmpq_t len, const fmpq *w) {
  fmpq_t t;
  fmpz_t rn, rd;
  int ok;
  fmpq_init(t);
  fmpz_init(rn);
  fmpz_init(rd);
  fmpq_zero(len);
  for (int k = 0; k < 3; k++)
    fmpq_addmul(len, w + k, w + k);
  ok = !fmpq_is_zero(len) && fmpz_is_square(fmpq_numref(len)) && fmpz_is_square(fmpq_denref(len));
  if (ok) {
    fmpz_sqrt(rn, fmpq_numref(len));
    fmpz_sqrt(rd, fmpq_denref(len));
    fmpq_set_fmpz_frac(len, rn, rd);
  }
  fmpq_clear(t);
  fmpz_clear(rn);
  fmpz_clear(rd);
  return ok;
}

/* Entry (i, j) of cos I + sin [k]x + (1 - cos) k k^T. */
static void rotation_entry(fmpq_t out, int i, int j, const fmpq *k, const fmpq_t c,
                           const fmpq_t s) {
  fmpq_t t;
  fmpq_init(t);
  fmpq_one(t);
  fmpq_sub(t, t, c);
  fmpq_mul(t, t, k + i);
  fmpq_mul(out, t, k + j);
  if (i == j)
    fmpq_add(out, out, c);
  else {
    int l = 3 - i - j, sign = ((j - i + 3) % 3 == 1) ? -1 : 1; /* [k]x(0,1) = -k2 */
    fmpq_mul(t, s, k + l);
    if (sign < 0)
      fmpq_sub(out, out, t);
    else
      fmpq_add(out, out, t);
  }
  fmpq_clear(t);
}

swarf_status swarf_xmotion_set(swarf_xmotion *m, const fmpq *w, const fmpq *tdot, const fmpq_t B) {
  fmpq_t len, c, s, d;
  int ok;
  fmpq_init(len);
  fmpq_init(c);
  fmpq_init(s);
  fmpq_init(d);
  ok = axis_length(len, w);
  if (ok) {
    fmpq_mul(d, B, B);
    fmpq_one(c);
    fmpq_sub(c, c, d); /* 1 - B^2 */
    fmpq_add_si(d, d, 1);
    fmpq_div(c, c, d);
    fmpq_mul_2exp(s, B, 1);
    fmpq_div(s, s, d);
    for (int k = 0; k < 3; k++)
      fmpq_div(m->omega + k, w + k, len);
    for (int i = 0; i < 3; i++)
      for (int j = 0; j < 3; j++)
        rotation_entry(m->U + 3 * i + j, i, j, m->omega, c, s);
    for (int j = 0; j < 3; j++) { /* v = U^T tdot */
      fmpq_zero(m->v + j);
      for (int i = 0; i < 3; i++)
        fmpq_addmul(m->v + j, m->U + 3 * i + j, tdot + i);
      fmpq_set(m->tdot + j, tdot + j);
    }
    fmpq_set(m->B, B);
  }
  fmpq_clear(len);
  fmpq_clear(c);
  fmpq_clear(s);
  fmpq_clear(d);
  return ok ? SWARF_OK : SWARF_ERR_ARG;
}
