/* SPDX-License-Identifier: MPL-2.0 */
/* exact_private.h -- the exact path's insides, shared by its files only.
 *
 *   exact_qr.c      Q(sqrt r) numbers.
 *   exact_qrpoly.c  polynomials over Q(sqrt r).
 *   exact_quad.c    rational quadratics: QSS, x_h, convexity, f (eq. 11).
 *   exact_motion.c  rational rotations with v and omega.
 *   exact_delta.c   slice lines A, B, C, Delta(z), certified roots, topology.
 *   exact_elm.c     Lemma 1's P, the cubic, R, the pencil k, l, m, D.
 *   exact_check.c   points of the parameterization, identity check.
 *   exact_report.c  the text report, and the top-level compute.
 */
#ifndef SWARF_EXACT_PRIVATE_H
#define SWARF_EXACT_PRIVATE_H

#include "envelope_exact.h"

/* sqrt(x) = q sqrt(r) with r squarefree (r = 1 when x is a square); x >= 0. */
void swarf_exact_sqrt_split(fmpz_t r, fmpq_t q, const fmpq_t x);

/* A, B, C of f per z-slice; -1 when f has x^2, y^2 or xy terms. */
int swarf_exact_slice_lines(swarf_envelope_exact *E);

/* Delta, its factorization, roots in [-1, 1] and components. -1: out of memory. */
int swarf_exact_delta_roots(swarf_envelope_exact *E);

/* The ELM steps for a curve (E->ncomp > 0). Returns 0, or -1 when no usable
 * rational slice z0 was found. */
int swarf_exact_elm(swarf_envelope_exact *E);

/* Gauss point of branch s at rational z in Q(sqrt rz). Returns 1 for a real
 * point, 0 when Delta(z) < 0 or A = B = 0. */
int swarf_exact_slice_point(const swarf_envelope_exact *E, const fmpq_t z, int s, fmpz_t rz,
                            swarf_qr n[3]);

#endif
