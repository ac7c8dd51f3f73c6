/* SPDX-License-Identifier: MPL-2.0 */
/* cli_envelope.c -- `swarf envelope`: the characteristic curve of a moving
 * QSS of revolution (paper eq. 12), or of any cutter (--tool), at one instant, by the fast path
 * (engine.h) or, with --exact, by the exact path (envelope_exact.h), which
 * prints every intermediate result for checking against the paper.
 *
 * The motion is U(alpha), the rotation by alpha about the axis through the
 * origin with direction --axis at unit angular speed, and t(alpha) =
 * alpha tdot; the instant is given by B = tan(alpha / 2). This file owns the
 * option values and everything it allocates.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "engine.h"
#include "envelope_exact.h"
#include "swarf_sim.h"

static const char envelope_help[] =
    "usage: swarf envelope --qss A,B,C,D,E,F --axis WX,WY,WZ --tdot VX,VY,VZ --half-angle B\n"
    "       swarf envelope --tool SPEC --axis WX,WY,WZ --tdot VX,VY,VZ --half-angle B [--points "
    "N]\n"
    "                      [--exact] [--at-z Z1,Z2,...] [--points N]\n"
    "\n"
    "The characteristic curve of the QSS h = A(x^2+y^2) + Bz^2 + Cx + Dy + Ez + F (paper\n"
    "eq. 12) under the rotation by alpha about the axis through the origin with direction\n"
    "--axis (unit angular speed) and the translation t(alpha) = alpha * tdot, at the\n"
    "instant B = tan(alpha/2). Numbers are rationals: 2, -1/3, 0.25.\n"
    "  --exact     exact arithmetic: f and g, P, the cubic, k, l, m, D(s), Delta(z) and\n"
    "              its certified roots (needs an axis of rational length, e.g. 2,1,2)\n"
    "  --at-z      print the curve's points at these slices n_z = Z as CSV\n"
    "  --points N  print N slices per component, spread over its z range, as CSV\n"
    "  --tool SPEC instead of --qss: any cutter of `swarf simulate --tool` (vee,D6,A90;\n"
    "              lollipop,D6,K3; qss,2,3,0,0; ...; a leading T<n>= is optional) in its\n"
    "              own frame (tip at the origin); --points N prints N points of each\n"
    "              component of its curve (chord tolerance 1e-3 mm), `branch` then being\n"
    "              the component's number; --exact and --at-z need --qss\n"
    "CSV columns: z,branch,nx,ny,nz,X,Y,Z,Xw,Yw,Zw (moving-frame normal, moving-frame\n"
    "surface point, world point t + U x). Exit status 2 on bad options.\n";

typedef struct {
  fmpq h[6], w[3], td[3];
  fmpq_t B;
  fmpq *atz;
  int natz, points, exact;
  int use_tool; /* --tool given: the cutter below instead of the QSS */
  swarf_sim_tool tool;
} options;

/* p, p/q or a decimal (-1.25) into x. Returns 0 or -1. */
static int parse_rational(fmpq_t x, const char *s, size_t len) {
  char buf[128], *dot;
  if (len == 0 || len >= sizeof buf) return -1;
  memcpy(buf, s, len);
  buf[len] = 0;
  if (strspn(buf, "+-0123456789/.") != len) return -1;
  if ((dot = strchr(buf, '.')) != NULL) {
    size_t frac = strlen(dot + 1);
    fmpz_t den;
    if (strchr(buf, '/') || frac > 60 || strchr(dot + 1, '.')) return -1;
    memmove(dot, dot + 1, frac + 1);
    if (buf[0] == '+') buf[0] = '0';
    if (fmpz_set_str(fmpq_numref(x), buf, 10) != 0) return -1;
    fmpz_init(den);
    fmpz_ui_pow_ui(den, 10, frac);
    fmpz_set(fmpq_denref(x), den);
    fmpz_clear(den);
    fmpq_canonicalise(x);
    return 0;
  }
  if (buf[0] == '+') buf[0] = '0';
  if (fmpq_set_str(x, buf, 10) != 0 || fmpz_is_zero(fmpq_denref(x))) return -1;
  fmpq_canonicalise(x);
  return 0;
}

/* A comma-separated list of exactly n rationals (n < 0: any count >= 1,
 * allocated into *out). Returns the count, or -1. */
static int parse_list(const char *s, fmpq *x, int n, fmpq **out) {
  int count = 0;
  for (const char *p = s;; count++) {
    const char *end = strchr(p, ',');
    size_t len = end ? (size_t)(end - p) : strlen(p);
    if (n < 0) {
      fmpq *mem = realloc(*out, (count + 1) * sizeof *mem);
      if (mem == NULL) return -1;
      *out = x = mem;
      fmpq_init(x + count);
    } else if (count >= n) {
      return -1;
    }
    if (parse_rational(x + count, p, len) != 0) return n < 0 ? -(count + 2) : -1;
    if (end == NULL) break;
    p = end + 1;
  }
  return n < 0 || count + 1 == n ? count + 1 : -1;
}

static int bad(const char *flag, const char *what) {
  fprintf(stderr, "swarf envelope: %s: %s\n(see swarf envelope --help)\n", flag, what);
  return 2;
}

static int parse_options(options *o, int argc, char **argv) {
  int have[4] = {0, 0, 0, 0};
  for (int i = 1; i < argc; i++) {
    const char *a = argv[i], *val = i + 1 < argc ? argv[i + 1] : NULL;
    if (!strcmp(a, "--exact")) {
      o->exact = 1;
      continue;
    }
    if (val == NULL) return bad(a, "unknown option or missing value");
    i++;
    if (!strcmp(a, "--qss")) {
      if (o->use_tool) return bad(a, "give --qss or --tool, not both");
      have[0] = parse_list(val, o->h, 6, NULL) == 6;
    } else if (!strcmp(a, "--tool")) {
      char spec[256];
      swarf_error err;
      if (have[0]) return bad(a, "give --qss or --tool, not both");
      snprintf(spec, sizeof spec, "%s%s", (val[0] == 'T' || val[0] == 't') ? "" : "T1=", val);
      swarf_error_init(&err);
      if (swarf_sim_parse_tool(spec, &o->tool, &err) != SWARF_OK) return bad(a, err.message);
      have[0] = o->use_tool = 1;
      continue;
    } else if (!strcmp(a, "--axis"))
      have[1] = parse_list(val, o->w, 3, NULL) == 3;
    else if (!strcmp(a, "--tdot"))
      have[2] = parse_list(val, o->td, 3, NULL) == 3;
    else if (!strcmp(a, "--half-angle"))
      have[3] = parse_rational(o->B, val, strlen(val)) == 0;
    else if (!strcmp(a, "--at-z")) {
      o->natz = parse_list(val, NULL, -1, &o->atz);
      if (o->natz <= 0)
        return o->natz = o->natz < -1 ? -o->natz - 1 : 0, bad(a, "Z1,Z2,... rationals");
      for (int k = 0; k < o->natz; k++)
        if (fmpz_cmpabs(fmpq_numref(o->atz + k), fmpq_denref(o->atz + k)) > 0)
          return bad(a, "slices lie in [-1, 1]");
      continue;
    } else if (!strcmp(a, "--points")) {
      char *end;
      long n = strtol(val, &end, 10);
      if (*end || n < 1 || n > 100000) return bad(a, "N, an integer from 1 to 100000");
      o->points = (int)n;
      continue;
    } else
      return bad(a, "unknown option");
    if (!have[0] && !strcmp(a, "--qss")) return bad(a, "six rationals A,B,C,D,E,F");
    if (!have[1] && !strcmp(a, "--axis")) return bad(a, "three rationals WX,WY,WZ");
    if (!have[2] && !strcmp(a, "--tdot")) return bad(a, "three rationals VX,VY,VZ");
    if (!have[3] && !strcmp(a, "--half-angle")) return bad(a, "a rational B");
  }
  if (!have[0] || !have[1] || !have[2] || !have[3])
    return bad("options", "--qss (or --tool), --axis, --tdot and --half-angle are all required");
  if (o->use_tool && (o->exact || o->natz > 0))
    return bad(o->exact ? "--exact" : "--at-z", "works on --qss only (not with --tool)");
  if (fmpq_is_zero(o->w + 0) && fmpq_is_zero(o->w + 1) && fmpq_is_zero(o->w + 2))
    return bad("--axis", "the axis direction must not be zero");
  return 0;
}

/* The pose in double precision: alpha, t, U, v = U^T tdot, omega. */
typedef struct {
  double h[6], alpha, t[3], U[9], v[3], omega[3];
} pose;

static void make_pose(pose *p, const options *o) {
  double w[3], len = 0.0, c, s, td[3];
  for (int i = 0; i < 6; i++)
    p->h[i] = fmpq_get_d(o->h + i);
  for (int k = 0; k < 3; k++)
    w[k] = fmpq_get_d(o->w + k), len += w[k] * w[k];
  len = sqrt(len);
  p->alpha = 2.0 * atan(fmpq_get_d(o->B));
  c = cos(p->alpha), s = sin(p->alpha);
  for (int k = 0; k < 3; k++) {
    p->omega[k] = w[k] / len;
    td[k] = fmpq_get_d(o->td + k);
    p->t[k] = p->alpha * td[k];
  }
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) {
      const double *k = p->omega;
      double cross = i == j ? 0.0 : ((j - i + 3) % 3 == 1 ? -1.0 : 1.0) * k[3 - i - j];
      p->U[3 * i + j] = (i == j ? c : 0.0) + s * cross + (1.0 - c) * k[i] * k[j];
    }
  for (int j = 0; j < 3; j++)
    p->v[j] = p->U[j] * td[0] + p->U[3 + j] * td[1] + p->U[6 + j] * td[2];
}

/* One CSV row: the surface point of eq. 12 at n and its world image. */
static void print_row(const pose *p, double z, int branch, const double n[3]) {
  const double *h = p->h;
  double g[3] = {2 * h[0] * n[0] + h[2], 2 * h[0] * n[1] + h[3], 2 * h[1] * n[2] + h[4]};
  double hv = h[0] * (n[0] * n[0] + n[1] * n[1]) + h[1] * n[2] * n[2] + h[2] * n[0] + h[3] * n[1] +
              h[4] * n[2] + h[5];
  double gn = g[0] * n[0] + g[1] * n[1] + g[2] * n[2], x[3], wld[3];
  for (int k = 0; k < 3; k++)
    x[k] = hv * n[k] + g[k] - gn * n[k];
  for (int k = 0; k < 3; k++)
    wld[k] = p->t[k] + p->U[3 * k] * x[0] + p->U[3 * k + 1] * x[1] + p->U[3 * k + 2] * x[2];
  printf("%.17g,%+d,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g\n", z, branch, n[0], n[1],
         n[2], x[0], x[1], x[2], wld[0], wld[1], wld[2]);
}

/* Fast-path slice: the body moved by (C, D, 0) turns with v + omega x p. */
static int fast_slice(const pose *p, double z, double n[2][3]) {
  double vp[3] = {p->v[0] - p->omega[2] * p->h[3], p->v[1] + p->omega[2] * p->h[2],
                  p->v[2] + p->omega[0] * p->h[3] - p->omega[1] * p->h[2]};
  return swarf_char_gauss_slice(2.0 * (p->h[1] - p->h[0]) * z + p->h[4], vp, p->omega, z, n);
}

static void print_slice(const pose *p, const swarf_envelope_exact *E, const fmpq_t zq) {
  double z = fmpq_get_d(zq), n[2][3];
  int cnt;
  if (E != NULL) {
    swarf_qr nq[2][3];
    fmpz_t rz;
    fmpz_init(rz);
    for (int b = 0; b < 2; b++)
      for (int k = 0; k < 3; k++)
        swarf_qr_init(&nq[b][k]);
    cnt = swarf_envelope_exact_slice(E, zq, rz, nq);
    for (int b = 0; b < 2; b++)
      for (int k = 0; k < 3; k++)
        n[b][k] = swarf_qr_get_d(&nq[b][k], rz), swarf_qr_clear(&nq[b][k]);
    fmpz_clear(rz);
  } else {
    cnt = fast_slice(p, z, n);
  }
  for (int b = 0; b < cnt; b++)
    print_row(p, z, b == 0 ? 1 : -1, n[b]);
}

/* N slices per z range [lo, hi] (rationals from the doubles). */
static void print_ranges(const pose *p, const swarf_envelope_exact *E, const double *lo,
                         const double *hi, int nr, int N) {
  fmpq_t zq;
  arf_t a;
  fmpq_init(zq);
  arf_init(a);
  for (int c = 0; c < nr; c++)
    for (int j = 0; j < N; j++) {
      arf_set_d(a, lo[c] + (hi[c] - lo[c]) * (j + 0.5) / N);
      arf_get_fmpq(zq, a);
      print_slice(p, E, zq);
    }
  fmpq_clear(zq);
  arf_clear(a);
}

/* The fast path's components and their z ranges (between branch points). */
static int fast_summary(const pose *p, double *lo, double *hi, int max) {
  swarf_char_curve cc;
  double z[66], vp[3] = {p->v[0] - p->omega[2] * p->h[3], p->v[1] + p->omega[2] * p->h[2],
                         p->v[2] + p->omega[0] * p->h[3] - p->omega[1] * p->h[2]};
  swarf_qss q = {p->h[0], p->h[1], p->h[4], p->h[5]};
  int nb = swarf_char_branch_points_qss(&q, vp, p->omega, z + 1, 64), nr = 0, nc;
  swarf_char_curve_init(&cc);
  nc = (swarf_char_curve_compute_qss12(&cc, p->h, p->t, p->U, p->v, p->omega, 1e-3) == SWARF_OK
            ? (int)cc.ncomp
            : -1);
  printf("fast: components %d, points %zu (chord tolerance 1e-3)\nfast: branch points", nc, cc.len);
  nb = nb > 64 ? 64 : nb;
  for (int i = 1; i <= nb; i++)
    printf(" %.15g", z[i]);
  printf("\n");
  z[0] = -1.0, z[nb + 1] = 1.0;
  for (int i = 0; i <= nb && nr < max; i++) {
    double n[2][3];
    if (fast_slice(p, 0.5 * (z[i] + z[i + 1]), n) == 2) lo[nr] = z[i], hi[nr++] = z[i + 1];
  }
  swarf_char_curve_clear(&cc);
  return nr;
}

static int run_exact(const options *o, const pose *p, swarf_envelope_exact *E) {
  swarf_xquad q;
  swarf_xmotion m;
  char *rep;
  int rc = 0;
  swarf_xquad_init(&q);
  swarf_xmotion_init(&m);
  swarf_xquad_set_revolution(&q, o->h);
  if (swarf_xmotion_set(&m, o->w, o->td, o->B) != SWARF_OK)
    rc = 2;
  else if (swarf_envelope_exact_compute(E, &q, m.v, m.omega) != SWARF_OK)
    rc = 1;
  if (rc == 2)
    fprintf(stderr, "swarf envelope: --axis: --exact needs an axis of rational length "
                    "(e.g. 2,1,2 or 0,3,4)\n");
  if (rc == 0) {
    printf("v: ");
    for (int k = 0; k < 3; k++)
      fmpq_print(m.v + k), printf(k < 2 ? ", " : "\n");
    printf("omega: ");
    for (int k = 0; k < 3; k++)
      fmpq_print(m.omega + k), printf(k < 2 ? ", " : "\n");
    rep = swarf_envelope_exact_report(E);
    if (rep == NULL)
      rc = 1;
    else
      fputs(rep, stdout), free(rep);
    if (E->kind == SWARF_ENV_CURVE)
      printf("Theorem 2 identity: %s\n",
             swarf_envelope_exact_check_elm(E) == 1 ? "holds" : "FAILS");
  }
  swarf_xmotion_clear(&m);
  swarf_xquad_clear(&q);
  return rc;
}

/* --tool: the cutter's curve at the pose, its summary and CSV rows. */
static int tool_curve(const pose *p, const swarf_cutter *c, int points) {
  swarf_char_curve cc;
  char desc[160];
  swarf_char_curve_init(&cc);
  swarf_cutter_describe(c, desc, sizeof desc);
  printf("tool: %s\n", desc);
  if (swarf_char_curve_compute(&cc, c, p->t, p->U, p->v, p->omega, 1e-3) != SWARF_OK) {
    fprintf(stderr, "swarf envelope: out of memory\n");
    swarf_char_curve_clear(&cc);
    return 1;
  }
  printf("fast: components %zu, points %zu (chord tolerance 1e-3)\n", cc.ncomp, cc.len);
  if (points > 0) {
    printf("\nz,branch,nx,ny,nz,X,Y,Z,Xw,Yw,Zw\n");
    for (size_t k = 0; k < cc.ncomp; k++) {
      size_t a = cc.start[k], n = cc.start[k + 1] - a;
      for (int j = 0; j < points && n > 0; j++) {
        const swarf_char_point *q =
            &cc.pts[a + (size_t)((double)j * (n - 1) / (points > 1 ? points - 1 : 1))];
        printf("%.17g,%zu,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g\n", q->n[2], k + 1,
               q->n[0], q->n[1], q->n[2], q->x[0], q->x[1], q->x[2], q->w[0], q->w[1], q->w[2]);
      }
    }
  }
  swarf_char_curve_clear(&cc);
  return 0;
}

int swarf_cli_envelope(int argc, char **argv) {
  options o;
  pose p;
  swarf_envelope_exact E;
  double lo[64], hi[64];
  int rc, nr;
  for (int i = 1; i < argc; i++)
    if (!strcmp(argv[i], "--help") || !strcmp(argv[i], "-h"))
      return fputs(envelope_help, stdout), 0;
  memset(&o, 0, sizeof o);
  for (int i = 0; i < 6; i++)
    fmpq_init(o.h + i);
  for (int i = 0; i < 3; i++)
    fmpq_init(o.w + i), fmpq_init(o.td + i);
  fmpq_init(o.B);
  swarf_envelope_exact_init(&E);
  rc = parse_options(&o, argc, argv);
  if (rc == 0) {
    make_pose(&p, &o);
    printf("alpha: %.17g\nv: %.17g, %.17g, %.17g\nomega: %.17g, %.17g, %.17g\n", p.alpha, p.v[0],
           p.v[1], p.v[2], p.omega[0], p.omega[1], p.omega[2]);
    if (o.use_tool)
      rc = tool_curve(&p, &o.tool.cutter, o.points), nr = 0;
    else
      nr = fast_summary(&p, lo, hi, 64);
    if (o.exact) rc = run_exact(&o, &p, &E);
  }
  if (rc == 0 && !o.use_tool && (o.natz > 0 || o.points > 0)) {
    printf("\nz,branch,nx,ny,nz,X,Y,Z,Xw,Yw,Zw\n");
    for (int k = 0; k < o.natz; k++)
      print_slice(&p, o.exact ? &E : NULL, o.atz + k);
    if (o.points > 0 && o.exact)
      print_ranges(&p, &E, E.comp_lo, E.comp_hi, E.ncomp, o.points);
    else if (o.points > 0)
      print_ranges(&p, NULL, lo, hi, nr, o.points);
  }
  swarf_envelope_exact_clear(&E);
  for (int i = 0; i < 6; i++)
    fmpq_clear(o.h + i);
  for (int i = 0; i < 3; i++)
    fmpq_clear(o.w + i), fmpq_clear(o.td + i);
  fmpq_clear(o.B);
  for (int k = 0; k < o.natz; k++)
    fmpq_clear(o.atz + k);
  free(o.atz);
  flint_cleanup();
  return rc;
}
