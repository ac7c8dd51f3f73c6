/* SPDX-License-Identifier: MPL-2.0 */
/* charqssgen_sweep.c -- the sweep that finds the topology of a general QSS's
 * characteristic curve f = n^T M n + L . n = 0 on the unit sphere.
 *
 * In a frame with axis e3, n = sin(phi) (cos(theta) e1 + sin(theta) e2) +
 * cos(phi) e3, f on the slice phi is a trigonometric polynomial of degree 2
 * in theta; with u = tan(theta / 2) (and the half circle around theta = pi
 * rotated by pi) its roots are those of two quartics on [-1, 1]. The number
 * of roots changes only at branch points: sampled, then bisected to adjacent
 * doubles. Roots are kept sorted in [-pi, pi), so the order also changes
 * where a strand crosses the cut theta = pi: those crossings are the roots
 * of f on the half meridian theta = pi, again a trigonometric quadratic. At
 * each event the roots on its two sides are matched (a cyclic shift, and the
 * pair that meets at a branch point). Works on caller-owned values only.
 */
#include <stdlib.h>
#include <string.h>

#include "engine_private.h"

#define PI 3.14159265358979323846
#define SAMPLES 32
#define MIN_WIDTH 1e-7 /* narrowest phi interval searched for a hidden pair */
#define CUT_GAP 1e-9   /* half width of the bracket around a cut crossing */

/* Roots in [-pi, pi) of c0 + c1 cos + s1 sin + c2 cos 2t + s2 sin 2t, c = {c0, c1, s1, c2, s2}. */
static int trig2_roots(const double c[5], double *th) {
  int n = 0;
  for (int half = 0; half < 2; half++) {
    double sg = half ? -1.0 : 1.0, c1 = sg * c[1], s1 = sg * c[2], u[4];
    double p[5] = {c[0] + c1 + c[3], 2 * s1 + 4 * c[4], 2 * c[0] - 6 * c[3], 2 * s1 - 4 * c[4],
                   c[0] - c1 + c[3]};
    int k = swarf_char_poly_roots(p, 4, -1.0, 1.0, u, 4);
    for (int i = 0; i < k && n < 8; i++) {
      double t = 2.0 * atan(u[i]) + (half ? PI : 0.0);
      th[n++] = t >= PI ? t - 2.0 * PI : t;
    }
  }
  for (int i = 1; i < n; i++) /* insertion sort */
    for (int j = i; j > 0 && th[j] < th[j - 1]; j--) {
      double x = th[j];
      th[j] = th[j - 1], th[j - 1] = x;
    }
  return n;
}

static void slice_coef(const swarf_gen_sweep *s, double phi, double c[5]) {
  const double *m = s->m, *l = s->l;
  double r = sin(phi), z = cos(phi);
  c[0] = 0.5 * r * r * (m[0] + m[4]) + m[8] * z * z + l[2] * z;
  c[1] = r * (2.0 * z * m[2] + l[0]);
  c[2] = r * (2.0 * z * m[5] + l[1]);
  c[3] = 0.5 * r * r * (m[0] - m[4]);
  c[4] = r * r * m[1];
}

int swarf_gen_slice_roots(const swarf_gen_sweep *s, double phi, double *theta) {
  double c[5], th[8];
  int n;
  slice_coef(s, phi, c);
  n = trig2_roots(c, th);
  if (n > 4) n = 4; /* a quartic on the sphere: more is rounding */
  memcpy(theta, th, (size_t)n * sizeof *th);
  return n;
}

/* G(phi) = min over theta of |(f, f_theta)|, zero exactly at a double root.
 * Its critical points in theta are the roots of f_theta or of f + f_thetatheta. */
static double min_critical(const swarf_gen_sweep *s, double phi) {
  double c[5], d[2][5], th[8], best = INFINITY;
  slice_coef(s, phi, c);
  d[0][0] = 0.0, d[0][1] = c[2], d[0][2] = -c[1], d[0][3] = 2.0 * c[4], d[0][4] = -2.0 * c[3];
  d[1][0] = c[0], d[1][1] = d[1][2] = 0.0, d[1][3] = -3.0 * c[3], d[1][4] = -3.0 * c[4];
  for (int k = 0; k < 2; k++) {
    int n = trig2_roots(d[k], th);
    if (n == 0) th[n++] = 0.0;
    for (int i = 0; i < n; i++) {
      double cs = cos(th[i]), sn = sin(th[i]), c2 = cos(2 * th[i]), s2 = sin(2 * th[i]);
      double f = c[0] + c[1] * cs + c[2] * sn + c[3] * c2 + c[4] * s2;
      double ft = -c[1] * sn + c[2] * cs - 2.0 * c[3] * s2 + 2.0 * c[4] * c2;
      best = fmin(best, sqrt(f * f + ft * ft));
    }
  }
  return best;
}

void swarf_gen_normal(const swarf_gen_sweep *s, double phi, double theta, double n[3]) {
  double r = sin(phi), z = cos(phi), a = r * cos(theta), b = r * sin(theta);
  for (int k = 0; k < 3; k++)
    n[k] = a * s->E[k] + b * s->E[3 + k] + z * s->E[6 + k];
}

static double fval(const double M[9], const double L[3], const double n[3]) {
  double f = 0.0;
  for (int i = 0; i < 3; i++)
    f += n[i] * (L[i] + M[3 * i] * n[0] + M[3 * i + 1] * n[1] + M[3 * i + 2] * n[2]);
  return f;
}

/* The frame: e3 the candidate axis with the largest min(|f(e3)|, |f(-e3)|). */
static void choose_frame(swarf_gen_sweep *s, const double M[9], const double L[3]) {
  static const double cand[6][3] = {
      {1, 1.4142135623730951, 1.7320508075688772},   {-1.7320508075688772, 1, 1.4142135623730951},
      {1.4142135623730951, -1.7320508075688772, 1},  {1, 1.7320508075688772, -2.2360679774997897},
      {2.2360679774997897, -1, -1.4142135623730951}, {-1.4142135623730951, -2.2360679774997897, 1}};
  double best = -1.0, *e1 = s->E, *e2 = s->E + 3, *e3 = s->E + 6, nn;
  for (int c = 0; c < 6; c++) {
    double e[3], fe, le, mn;
    nn = sqrt(cand[c][0] * cand[c][0] + cand[c][1] * cand[c][1] + cand[c][2] * cand[c][2]);
    for (int k = 0; k < 3; k++)
      e[k] = cand[c][k] / nn;
    fe = fval(M, L, e); /* f(e); f(-e) = f(e) - 2 L . e */
    le = L[0] * e[0] + L[1] * e[1] + L[2] * e[2];
    mn = fmin(fabs(fe), fabs(fe - 2.0 * le));
    if (mn > best) best = mn, memcpy(e3, e, sizeof e);
  }
  /* e1 = unit(x-ish axis minus its e3 part), e2 = e3 x e1 */
  e1[0] = 1.0 - e3[0] * e3[0], e1[1] = -e3[0] * e3[1], e1[2] = -e3[0] * e3[2];
  nn = sqrt(e1[0] * e1[0] + e1[1] * e1[1] + e1[2] * e1[2]);
  for (int k = 0; k < 3; k++)
    e1[k] /= nn;
  e2[0] = e3[1] * e1[2] - e3[2] * e1[1];
  e2[1] = e3[2] * e1[0] - e3[0] * e1[2];
  e2[2] = e3[0] * e1[1] - e3[1] * e1[0];
  for (int i = 0; i < 3; i++) {
    s->l[i] = s->E[3 * i] * L[0] + s->E[3 * i + 1] * L[1] + s->E[3 * i + 2] * L[2];
    for (int j = 0; j < 3; j++) {
      double v = 0.0;
      for (int p = 0; p < 3; p++)
        for (int q = 0; q < 3; q++)
          v += s->E[3 * i + p] * M[3 * p + q] * s->E[3 * j + q];
      s->m[3 * i + j] = v;
    }
  }
}

static int add_event(swarf_gen_sweep *s, double lo, double hi, int branch) {
  if (s->nev >= SWARF_GEN_MAX_EVENTS) return -1;
  s->a[s->nev] = lo, s->b[s->nev] = hi, s->branch[s->nev] = branch;
  s->nev++;
  return 0;
}

static int count(const swarf_gen_sweep *s, double phi) {
  double th[4];
  return swarf_gen_slice_roots(s, phi, th);
}

/* Branch points in [lo, hi], where the root count goes from nlo to nhi and
 * G (min_critical) is mlo, mhi. G is lip-Lipschitz in phi (lip bounds
 * |d(f, f_theta)/dphi|), so an interval with equal counts and
 * mlo + mhi > lip (hi - lo) holds no double root; others are split, down to MIN_WIDTH when the
 * counts agree and to adjacent doubles when they differ. */
static int scan(swarf_gen_sweep *s, double lo, int nlo, double mlo, double hi, int nhi,
                double mhi) {
  double mid = 0.5 * (lo + hi), mm;
  int nm;
  if (nlo == nhi && (mlo + mhi > s->lip * (hi - lo) || hi - lo < MIN_WIDTH)) return 0;
  if (mid <= lo || mid >= hi) return add_event(s, lo, hi, 1);
  nm = count(s, mid);
  mm = min_critical(s, mid);
  if (scan(s, lo, nlo, mlo, mid, nm, mm) != 0) return -1;
  return scan(s, mid, nm, mm, hi, nhi, mhi);
}

/* Crossings of the cut: f on n = -sin(phi) e1 + cos(phi) e3, phi in (0, pi). */
static int find_cuts(swarf_gen_sweep *s) {
  const double *m = s->m, *l = s->l;
  double c[5] = {0.5 * (m[0] + m[8]), l[2], -l[0], 0.5 * (m[8] - m[0]), -m[2]}, ph[8];
  int n = trig2_roots(c, ph);
  for (int i = 0; i < n; i++)
    if (ph[i] > 2 * CUT_GAP && ph[i] < PI - 2 * CUT_GAP)
      if (add_event(s, ph[i] - CUT_GAP, ph[i] + CUT_GAP, 0) != 0) return -1;
  return 0;
}

static double circ(double a, double b) {
  double d = fabs(a - b);
  return d > PI ? 2.0 * PI - d : d;
}

/* Match the n angles A[ia[t]] to B[ib[t]] by the best cyclic shift. */
static void match(const double *A, const int *ia, const double *B, const int *ib, int n, int *a2b,
                  int *b2a) {
  int best = 0;
  double bd = INFINITY;
  for (int sh = 0; sh < n; sh++) {
    double d = 0.0;
    for (int t = 0; t < n; t++)
      d += circ(A[ia[t]], B[ib[(t + sh) % n]]);
    if (d < bd) bd = d, best = sh;
  }
  for (int t = 0; t < n; t++) {
    a2b[ia[t]] = ib[(t + best) % n];
    b2a[ib[(t + best) % n]] = ia[t];
  }
}

/* The pair of circularly adjacent angles closest together: p and p + 1 mod n. */
static int closest_pair(const double *A, int n) {
  int best = 0;
  double bd = INFINITY;
  for (int p = 0; p < n; p++) {
    double d = circ(A[p], A[(p + 1) % n]);
    if (d < bd) bd = d, best = p;
  }
  return best;
}

/* map: from the side with n roots to the side with n - 2 (or n). */
static void link_event(const double *A, int na, const double *B, int nb, int *a2b, int *b2a) {
  int ia[4], ib[4];
  if (na == nb) {
    for (int i = 0; i < na; i++)
      ia[i] = ib[i] = i;
    match(A, ia, B, ib, na, a2b, b2a);
    return;
  }
  if (na < nb) {
    link_event(B, nb, A, na, b2a, a2b);
    return;
  }
  int p = closest_pair(A, na), q = (p + 1) % na;
  a2b[p] = -1 - q, a2b[q] = -1 - p;
  for (int t = 0; t < na - 2; t++)
    ia[t] = (q + 1 + t) % na;
  for (int t = 0; t < nb; t++)
    ib[t] = t;
  match(A, ia, B, ib, nb, a2b, b2a);
}

static void sort_events(swarf_gen_sweep *s) {
  for (int i = 1; i < s->nev; i++)
    for (int j = i; j > 0 && s->a[j] < s->a[j - 1]; j--) {
      double x = s->a[j], y = s->b[j];
      int br = s->branch[j];
      s->a[j] = s->a[j - 1], s->b[j] = s->b[j - 1], s->branch[j] = s->branch[j - 1];
      s->a[j - 1] = x, s->b[j - 1] = y, s->branch[j - 1] = br;
    }
}

/* Turn the sorted events into intervals [a[k], b[k]] and link them. */
static int build_intervals(swarf_gen_sweep *s) {
  double lo[SWARF_GEN_MAX_EVENTS], hi[SWARF_GEN_MAX_EVENTS];
  int ne = s->nev;
  memcpy(lo, s->a, (size_t)ne * sizeof *lo);
  memcpy(hi, s->b, (size_t)ne * sizeof *hi);
  for (int k = 0; k + 1 < ne; k++)
    if (!(lo[k + 1] > hi[k])) return -1; /* overlapping events */
  s->nint = ne + 1;
  for (int k = 0; k <= ne; k++) {
    s->a[k] = k == 0 ? 0.0 : hi[k - 1];
    s->b[k] = k == ne ? PI : lo[k];
    s->nroot[k] = count(s, 0.5 * (s->a[k] + s->b[k]));
  }
  if (s->nroot[0] != 0 || s->nroot[ne] != 0) return -1; /* a strand at a pole */
  for (int k = 0; k < ne; k++) {
    double A[4], B[4];
    int na = swarf_gen_slice_roots(s, s->b[k], A), nb = swarf_gen_slice_roots(s, s->a[k + 1], B);
    if (na != s->nroot[k] || nb != s->nroot[k + 1] || (na != nb && !s->branch[k]) ||
        abs(na - nb) > 2)
      return -1;
    link_event(A, na, B, nb, s->map_r[k], s->map_l[k]);
  }
  return 0;
}

int swarf_gen_sweep_init(swarf_gen_sweep *s, const double M[9], const double L[3]) {
  double mm = 0.0, ll, mprev;
  int prev;
  memset(s, 0, sizeof *s);
  choose_frame(s, M, L);
  for (int i = 0; i < 9; i++)
    mm += s->m[i] * s->m[i];
  ll = sqrt(s->l[0] * s->l[0] + s->l[1] * s->l[1] + s->l[2] * s->l[2]);
  mm = sqrt(mm);
  s->lip = hypot(2.0 * mm + ll, 4.0 * mm + ll);
  prev = count(s, 0.0);
  mprev = min_critical(s, 0.0);
  for (int i = 1; i <= SAMPLES; i++) {
    double p0 = PI * (i - 1) / SAMPLES, p1 = PI * i / SAMPLES, m1 = min_critical(s, p1);
    int n1 = count(s, p1);
    if (scan(s, p0, prev, mprev, p1, n1, m1) != 0) return -1;
    prev = n1, mprev = m1;
  }
  if (find_cuts(s) != 0) return -1;
  sort_events(s);
  return build_intervals(s);
}
