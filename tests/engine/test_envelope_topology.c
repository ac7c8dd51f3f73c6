/* SPDX-License-Identifier: MPL-2.0 */
/* test_envelope_topology.c -- the fast path (double precision, engine.h)
 * certified by the exact path (envelope_exact.h) across thousands of random
 * rational QSS of revolution and motions (fixed seed): same number of
 * components, same branch points (the exact roots of Delta are certified
 * enclosures); every float point satisfies f = 0, g = 0 and v_h(n) . n = 0
 * to 1e-12 (relative to the size of the surface and velocity).
 */
#include <stdlib.h>

#include "check.h"
#include "exactkit.h"

#define CASES 3000
#define NEAR 1e-6 /* roots closer than this to each other or to +-1: near-degenerate */

static const double I3[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
static const double zero3[3] = {0, 0, 0};

/* f(n) and v_h(n) . n in double precision for eq. 12 coefficients h6. */
static void residuals(const double h6[6], const double v[3], const double w[3],
                      const swarf_char_point *p, double *f, double *vh) {
  const double *n = p->n;
  double g[3] = {2 * h6[0] * n[0] + h6[2], 2 * h6[0] * n[1] + h6[3], 2 * h6[1] * n[2] + h6[4]};
  double c[3], vx[3];
  tk_cross(w, g, c);
  *f = (v[0] + c[0]) * n[0] + (v[1] + c[1]) * n[1] + (v[2] + c[2]) * n[2];
  tk_cross(w, p->x, vx);
  *vh = (v[0] + vx[0]) * n[0] + (v[1] + vx[1]) * n[1] + (v[2] + vx[2]) * n[2];
}

/* The exact sign-changing roots, rounded; -1 when near-degenerate. */
static int exact_roots(const swarf_envelope_exact *E, double *z, int max) {
  int n = 0;
  for (int i = 0; i < E->nroots; i++) {
    double zi = arf_get_d(arb_midref(E->roots[i].z), ARF_RND_NEAR);
    if (E->roots[i].multiplicity % 2 == 0 || n >= max) return -1;
    if (fabs(fabs(zi) - 1.0) < NEAR || (n > 0 && zi - z[n - 1] < NEAR)) return -1;
    z[n++] = zi;
  }
  return n;
}

int main(void) {
  tk_rng rng = {0x70901093ULL};
  int compared = 0, skipped = 0, comp_bad = 0, root_bad = 0, pts = 0, pt_bad = 0;
  double worst_root = 0.0, worst_res = 0.0;
  swarf_char_curve cc;
  swarf_char_curve_init(&cc);
  for (int it = 0; it < CASES; it++) {
    fmpq h6[6];
    swarf_xquad q;
    swarf_xmotion m;
    swarf_envelope_exact E;
    double hd[6], v[3], w[3], ze[8], zf[8], scale;
    int ne, nf, nc;
    ek_vec_init(h6, 6);
    swarf_xquad_init(&q), swarf_xmotion_init(&m), swarf_envelope_exact_init(&E);
    ek_random_case(&rng, h6, &m, it % 3 == 0);
    swarf_xquad_set_revolution(&q, h6);
    swarf_envelope_exact_compute(&E, &q, m.v, m.omega);
    ek_vec_get_d(hd, h6, 6), ek_vec_get_d(v, m.v, 3), ek_vec_get_d(w, m.omega, 3);
    ne = exact_roots(&E, ze, 8);
    if ((E.kind != SWARF_ENV_CURVE && E.kind != SWARF_ENV_GREAT_CIRCLE) || ne < 0) {
      skipped++;
    } else {
      swarf_qss sq = {hd[0], hd[1], hd[4], hd[5]};
      double p[3] = {hd[2], hd[3], 0.0}, wp[3], vp[3];
      tk_cross(w, p, wp);
      for (int k = 0; k < 3; k++)
        vp[k] = v[k] + wp[k];
      nf = swarf_char_branch_points_qss(&sq, vp, w, zf, 8);
      nc = (swarf_char_curve_compute_qss12(&cc, hd, zero3, I3, v, w, 1e-3) == SWARF_OK
                ? (int)cc.ncomp
                : -1);
      compared++;
      comp_bad += nc != E.ncomp;
      if (nf != ne || nc != E.ncomp) {
        fprintf(stderr, "case %d: exact %d components, roots", it, E.ncomp);
        for (int i = 0; i < ne; i++)
          fprintf(stderr, " %.17g", ze[i]);
        fprintf(stderr, "; fast %d components, roots", nc);
        for (int i = 0; i < nf && i < 8; i++)
          fprintf(stderr, " %.17g", zf[i]);
        fputc('\n', stderr);
      }
      if (nf != ne)
        root_bad++;
      else
        for (int i = 0; i < ne; i++) {
          worst_root = fmax(worst_root, fabs(zf[i] - ze[i]));
          root_bad += fabs(zf[i] - ze[i]) > 1e-9;
        }
      scale = 1.0 + tk_dot(v, v) + 4.0 * (fabs(hd[0]) + fabs(hd[1])) + fabs(hd[2]) + fabs(hd[3]) +
              fabs(hd[4]) + fabs(hd[5]);
      for (size_t i = 0; i < cc.len; i++) {
        double f, vh, g = tk_dot(cc.pts[i].n, cc.pts[i].n) - 1.0;
        residuals(hd, v, w, &cc.pts[i], &f, &vh);
        worst_res = fmax(worst_res, fmax(fabs(f), fabs(vh)) / scale);
        pt_bad += fabs(f) > 1e-12 * scale || fabs(vh) > 1e-12 * scale || fabs(g) > 1e-12;
        pts++;
      }
    }
    swarf_xquad_clear(&q), swarf_xmotion_clear(&m), swarf_envelope_exact_clear(&E);
    ek_vec_clear(h6, 6);
  }
  printf("%d cases compared, %d degenerate or near-degenerate skipped; %d float points\n", compared,
         skipped, pts);
  printf("worst branch point difference %.3g, worst relative residual %.3g\n", worst_root,
         worst_res);
  CHECK(compared > CASES / 2, "most cases compared (%d)", compared);
  CHECK(comp_bad == 0, "component counts differ in %d cases", comp_bad);
  CHECK(root_bad == 0, "branch points differ in %d cases", root_bad);
  CHECK(pt_bad == 0, "%d of %d float points off f = g = v_h.n = 0", pt_bad, pts);
  swarf_char_curve_clear(&cc);
  flint_cleanup();
  return check_done();
}
