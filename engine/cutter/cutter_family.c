/* SPDX-License-Identifier: MPL-2.0 */
/* cutter_family.c -- the named cutter families (engine.h, swarf_cutter_make):
 * each family's numbers checked (the message names the parameter by its
 * letter in a tool spec and says why) and turned into hull pieces.
 *
 * Cutter frame: tip (lowest point) at the origin, axis +z. Angles arrive in
 * degrees. Caller-owned values only.
 */
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

#include "engine_private.h"

#define DEG (3.14159265358979323846 / 180.0)

void swarf_cutter_spec_init(swarf_cutter_spec *s) {
  if (s == NULL) return;
  s->shape = SWARF_CUTTER_FLAT;
  s->d = s->r = s->length = s->angle = s->tip = s->e = s->f = s->beta = s->h = s->neck = NAN;
  s->qa = s->qb = s->qe = s->qf = NAN;
}

#ifdef __GNUC__
__attribute__((format(printf, 3, 4)))
#endif
static swarf_status
bad(swarf_error *err, const char *letter, const char *fmt, ...) {
  char msg[400];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(msg, sizeof msg, fmt, ap);
  va_end(ap);
  if (err != NULL) swarf_error_at(err, NULL, 0, 0, letter);
  return swarf_error_set(err, SWARF_ERR_TOOL, "%s: %s", letter, msg);
}

static int given(double x) {
  return !isnan(x);
}

/* A positive finite number, or an error naming the letter. */
static swarf_status need_pos(double x, const char *letter, const char *what, swarf_error *err) {
  if (!given(x)) return bad(err, letter, "the %s is required", what);
  if (!isfinite(x) || !(x > 0.0)) return bad(err, letter, "the %s must be > 0 (got %g)", what, x);
  return SWARF_OK;
}

static swarf_status length_or(double *L, double dflt, double at_least, const char *why,
                              swarf_error *err) {
  if (!given(*L)) *L = dflt;
  if (!isfinite(*L) || !(*L > at_least))
    return bad(err, "L", "the length must be a finite number above %g (%s; got %g)", at_least, why,
               *L);
  return SWARF_OK;
}

static swarf_status finish_family(swarf_cutter *c, swarf_cutter_shape shape, swarf_error *err) {
  swarf_status st = swarf_cutter_finish(c, err);
  c->shape = shape;
  return st;
}

/* A sharp cone tip of included angle A up to diameter d, then a cylinder to L. */
static swarf_status pointed(swarf_cutter *c, const swarf_cutter_spec *s, swarf_cutter_shape shape,
                            double dflt_angle, swarf_error *err) {
  double A = given(s->angle) ? s->angle : dflt_angle, d = s->d, L = s->length, h, ta;
  double tip = shape == SWARF_CUTTER_CHAMFER && given(s->tip) ? s->tip : 0.0;
  swarf_status st;
  if ((st = need_pos(d, "D", "diameter", err)) != SWARF_OK) return st;
  if (!given(A)) return bad(err, "A", "the included angle is required (degrees, e.g. A90)");
  if (!(A > 0.0 && A < 180.0))
    return bad(err, "A", "the %s angle must be between 0 and 180 degrees (got %g)",
               shape == SWARF_CUTTER_VEE || shape == SWARF_CUTTER_CHAMFER ? "included" : "point",
               A);
  if (!isfinite(tip) || tip < 0.0 || !(tip < d))
    return bad(err, "T", "the tip diameter must be >= 0 and below D = %g (got %g)", d, tip);
  ta = tan(0.5 * A * DEG);
  h = 0.5 * (d - tip) / ta;
  if ((st = length_or(&L, fmax(4.0 * d, h), 0.0, "the cutting length", err)) != SWARF_OK) return st;
  swarf_cutter_begin(c);
  if (L < h) {
    const double k[2][3] = {{0.5 * tip, 0, 0}, {0.5 * tip + L * ta, L, 0}};
    st = swarf_cutter_add_hull(c, k, 2, err);
  } else {
    const double k[3][3] = {{0.5 * tip, 0, 0}, {0.5 * d, h, 0}, {0.5 * d, L, 0}};
    st = swarf_cutter_add_hull(c, k, L > h ? 3 : 2, err);
  }
  if (st != SWARF_OK) return st;
  c->param[0] = d, c->param[1] = A * DEG, c->param[2] = L, c->param[3] = tip;
  return finish_family(c, shape, err);
}

static swarf_status taper(swarf_cutter *c, const swarf_cutter_spec *s, swarf_error *err) {
  double d = s->d, A = s->angle, R = given(s->r) ? s->r : 0.0, L = s->length, t0r, t0z, rl;
  swarf_status st;
  if ((st = need_pos(d, "D", "tip diameter", err)) != SWARF_OK) return st;
  if (!given(A)) return bad(err, "A", "the taper half-angle is required (degrees)");
  if (!(A >= 0.0 && A < 90.0))
    return bad(err, "A", "the taper half-angle must be in [0, 90) (got %g)", A);
  if (!(R >= 0.0 && R <= 0.5 * d))
    return bad(err, "R", "the tip corner radius must be in [0, D/2 = %g] (got %g)", 0.5 * d, R);
  t0r = 0.5 * d - R + R * cos(A * DEG);
  t0z = R - R * sin(A * DEG);
  if ((st = length_or(&L, 4.0 * d, t0z, "above the corner", err)) != SWARF_OK) return st;
  rl = t0r + (L - t0z) * tan(A * DEG);
  swarf_cutter_begin(c);
  {
    const double k[2][3] = {{0.5 * d - R, R, R}, {rl, L, 0}};
    if ((st = swarf_cutter_add_hull(c, k, 2, err)) != SWARF_OK) return st;
  }
  c->corner_radius = R;
  c->param[0] = d, c->param[1] = A * DEG, c->param[2] = R, c->param[3] = L;
  return finish_family(c, SWARF_CUTTER_TAPER, err);
}

static swarf_status apt(swarf_cutter *c, const swarf_cutter_spec *s, swarf_error *err) {
  double d = s->d, R = s->r, E = s->e, F = s->f, al = s->angle, be = s->beta, H = s->h;
  double tol, want, t0r, t0z, rh;
  swarf_status st;
  if ((st = need_pos(d, "D", "diameter", err)) != SWARF_OK) return st;
  if (!given(R) || !isfinite(R) || R < 0.0) return bad(err, "R", "the corner radius must be >= 0");
  if (!given(E) || !isfinite(E) || E < 0.0)
    return bad(err, "E", "the corner centre's distance from the axis must be >= 0");
  if (!given(F) || !isfinite(F)) return bad(err, "F", "the corner centre's height is required");
  if (!given(al) || !(al >= 0.0 && al < 90.0))
    return bad(err, "A", "alpha (bottom angle from the horizontal) must be in [0, 90) degrees");
  if (!given(be) || !(be > -90.0 && be < 90.0))
    return bad(err, "B", "beta (side angle from the axis) must be in (-90, 90) degrees");
  if ((st = need_pos(H, "H", "height", err)) != SWARF_OK) return st;
  al *= DEG, be *= DEG;
  tol = 1e-3 + 1e-3 * d;
  want = (R + E * sin(al)) / cos(al);
  if (fabs(F - want) > tol)
    return bad(err, "F",
               "with R, E and alpha the bottom line passes through the tip only for "
               "F = (R + E sin A) / cos A = %.6g (got %g)",
               want, F);
  want = 2.0 * (E + R / cos(be));
  if (fabs(d - want) > tol)
    return bad(err, "D",
               "the diameter at the corner centre's height is 2 (E + R / cos B) = %.6g "
               "(got %g)",
               want, d);
  t0r = E + R * cos(be);
  t0z = F - R * sin(be);
  if (!(H > t0z)) return bad(err, "H", "the height must be above the side's start at %g", t0z);
  rh = t0r + (H - t0z) * tan(be);
  if (!(rh >= 0.0)) return bad(err, "H", "the side reaches the axis below H (beta < 0)");
  swarf_cutter_begin(c);
  {
    const double k[3][3] = {{E, F, R}, {rh, H, 0}, {0, 0, 0}};
    if ((st = swarf_cutter_add_hull(c, k, al > 0.0 ? 3 : 2, err)) != SWARF_OK) return st;
  }
  c->corner_radius = R;
  c->param[0] = d, c->param[1] = R, c->param[2] = E, c->param[3] = F, c->param[4] = al;
  c->param[5] = be, c->param[6] = H;
  return finish_family(c, SWARF_CUTTER_APT, err);
}

/* A thinner neck of diameter n from height z0 to L on a head piece. */
static swarf_status neck(swarf_cutter *c, double n, double z0, double L, swarf_error *err) {
  return swarf_cutter_add_frustum(c, z0, 0.5 * n, L, 0.5 * n, err);
}

static swarf_status lollipop(swarf_cutter *c, const swarf_cutter_spec *s, swarf_error *err) {
  double d = s->d, n = s->neck, L = s->length;
  const double ball[1][3] = {{0, 0.5 * d, 0.5 * d}};
  swarf_status st;
  if ((st = need_pos(d, "D", "sphere diameter", err)) != SWARF_OK) return st;
  if ((st = need_pos(n, "K", "neck diameter", err)) != SWARF_OK) return st;
  if (!(n < d))
    return bad(err, "K", "the neck must be thinner than the sphere D = %g (got %g)", d, n);
  if ((st = length_or(&L, 4.0 * d, d, "above the sphere", err)) != SWARF_OK) return st;
  swarf_cutter_begin(c);
  if ((st = swarf_cutter_add_hull(c, ball, 1, err)) != SWARF_OK) return st;
  if ((st = neck(c, n, 0.5 * d, L, err)) != SWARF_OK) return st;
  c->corner_radius = 0.5 * d;
  c->param[0] = d, c->param[1] = n, c->param[2] = L;
  return finish_family(c, SWARF_CUTTER_LOLLIPOP, err);
}

static swarf_status dovetail(swarf_cutter *c, const swarf_cutter_spec *s, swarf_error *err) {
  double d = s->d, A = s->angle, H = s->h, n = s->neck, L = s->length, top;
  swarf_status st;
  if ((st = need_pos(d, "D", "bottom diameter", err)) != SWARF_OK) return st;
  if (!given(A) || !(A > 0.0 && A < 90.0))
    return bad(err, "A", "the flank angle (to the base) must be in (0, 90) degrees");
  if ((st = need_pos(H, "H", "flank height", err)) != SWARF_OK) return st;
  top = d - 2.0 * H / tan(A * DEG);
  if (!(top > 0.0))
    return bad(err, "H", "the flanks meet below H: at A = %g the height must be below %g", A,
               0.5 * d * tan(A * DEG));
  if (!given(n)) n = top;
  if (!(n > 0.0 && n <= top))
    return bad(err, "K", "the neck diameter must be in (0, %g] (the flank's top; got %g)", top, n);
  if ((st = length_or(&L, H + 2.0 * d, H, "above the flanks", err)) != SWARF_OK) return st;
  swarf_cutter_begin(c);
  if ((st = swarf_cutter_add_frustum(c, 0.0, 0.5 * d, H, 0.5 * top, err)) != SWARF_OK) return st;
  if ((st = neck(c, n, H, L, err)) != SWARF_OK) return st;
  c->param[0] = d, c->param[1] = A * DEG, c->param[2] = H, c->param[3] = n, c->param[4] = L;
  return finish_family(c, SWARF_CUTTER_DOVETAIL, err);
}

static swarf_status tslot(swarf_cutter *c, const swarf_cutter_spec *s, swarf_error *err) {
  double d = s->d, H = s->h, n = s->neck, L = s->length;
  swarf_status st;
  if ((st = need_pos(d, "D", "diameter", err)) != SWARF_OK) return st;
  if ((st = need_pos(H, "H", "disk thickness", err)) != SWARF_OK) return st;
  if ((st = need_pos(n, "K", "neck diameter", err)) != SWARF_OK) return st;
  if (!(n < d))
    return bad(err, "K", "the neck must be thinner than the disk D = %g (got %g)", d, n);
  if ((st = length_or(&L, H + 2.0 * d, H, "above the disk", err)) != SWARF_OK) return st;
  swarf_cutter_begin(c);
  if ((st = swarf_cutter_add_frustum(c, 0.0, 0.5 * d, H, 0.5 * d, err)) != SWARF_OK) return st;
  if ((st = neck(c, n, H, L, err)) != SWARF_OK) return st;
  c->param[0] = d, c->param[1] = H, c->param[2] = n, c->param[3] = L;
  return finish_family(c, SWARF_CUTTER_TSLOT, err);
}

static swarf_status qss(swarf_cutter *c, const swarf_cutter_spec *s, swarf_error *err) {
  swarf_qss q = {s->qa, s->qb, s->qe, s->qf};
  swarf_status st;
  swarf_cutter_begin(c);
  if ((st = swarf_cutter_add_qss(c, &q, 0.0, err)) != SWARF_OK) return st;
  c->piece[0].lift = -c->piece[0].zlo; /* lowest point to the tip */
  c->piece[0].zhi -= c->piece[0].zlo;
  c->piece[0].zw0 = c->piece[0].zw1 = c->piece[0].zw0 + c->piece[0].lift;
  c->piece[0].zlo = 0.0;
  c->param[0] = q.a, c->param[1] = q.b, c->param[2] = q.e, c->param[3] = q.f;
  return finish_family(c, SWARF_CUTTER_QSS, err);
}

static swarf_status classic(swarf_cutter *c, const swarf_cutter_spec *s, swarf_error *err) {
  swarf_error e;
  swarf_error_init(&e);
  if (swarf_cutter_init(c, s->shape, given(s->d) ? s->d : 0.0, given(s->r) ? s->r : 0.0,
                        given(s->length) ? s->length : 0.0, &e) != SWARF_OK)
    return bad(err, e.word[0] ? e.word : "D", "%s", e.message);
  return SWARF_OK;
}

/* The sizes every family shares: none beyond a metre, a diameter of at least
 * a micrometre, a length given > 0 (left out, it takes the default). */
static swarf_status check_sizes(const swarf_cutter_spec *s, swarf_error *err) {
  const double v[] = {s->d, s->r, s->length, s->tip, s->e, s->f, s->h, s->neck};
  static const char *const letter[] = {"D", "R", "L", "T", "E", "F", "H", "K"};
  for (size_t i = 0; i < sizeof v / sizeof v[0]; i++)
    if (given(v[i]) && isfinite(v[i]) && fabs(v[i]) > SWARF_CUTTER_MAX_MM)
      return bad(err, letter[i],
                 "%g mm is beyond any cutter (at most %g mm; a typo or a unit slip)", v[i],
                 SWARF_CUTTER_MAX_MM);
  if (given(s->d) && s->d > 0 && s->d < SWARF_CUTTER_MIN_MM)
    return bad(err, "D", "the diameter %g mm is below %g mm (a typo or a unit slip)", s->d,
               SWARF_CUTTER_MIN_MM);
  if (given(s->length) && !(s->length > 0))
    return bad(err, "L", "the length must be > 0 (got %g); leave L out for the default", s->length);
  return SWARF_OK;
}

swarf_status swarf_cutter_make(swarf_cutter *c, const swarf_cutter_spec *s, swarf_error *err) {
  if (c == NULL || s == NULL) return swarf_error_set(err, SWARF_ERR_ARG, "no cutter or spec");
  if (s->shape != SWARF_CUTTER_QSS && check_sizes(s, err) != SWARF_OK) return SWARF_ERR_TOOL;
  switch (s->shape) {
  case SWARF_CUTTER_FLAT:
  case SWARF_CUTTER_BALL:
  case SWARF_CUTTER_BULL:
    return classic(c, s, err);
  case SWARF_CUTTER_VEE:
    return pointed(c, s, SWARF_CUTTER_VEE, NAN, err);
  case SWARF_CUTTER_DRILL:
    return pointed(c, s, SWARF_CUTTER_DRILL, 118.0, err);
  case SWARF_CUTTER_SPOT:
    return pointed(c, s, SWARF_CUTTER_SPOT, 90.0, err);
  case SWARF_CUTTER_CHAMFER:
    return pointed(c, s, SWARF_CUTTER_CHAMFER, NAN, err);
  case SWARF_CUTTER_TAPER:
    return taper(c, s, err);
  case SWARF_CUTTER_APT:
    return apt(c, s, err);
  case SWARF_CUTTER_LOLLIPOP:
    return lollipop(c, s, err);
  case SWARF_CUTTER_DOVETAIL:
    return dovetail(c, s, err);
  case SWARF_CUTTER_TSLOT:
    return tslot(c, s, err);
  case SWARF_CUTTER_QSS:
    return qss(c, s, err);
  default:
    return swarf_error_set(err, SWARF_ERR_TOOL, "unknown cutter family");
  }
}

static const char *family_name(swarf_cutter_shape s) {
  static const char *names[] = {"flat",  "ball", "bull",     "vee",      "drill", "spot", "chamfer",
                                "taper", "apt",  "lollipop", "dovetail", "tslot", "qss",  "body"};
  return (unsigned)s < sizeof names / sizeof names[0] ? names[s] : "?";
}

void swarf_cutter_describe(const swarf_cutter *c, char *buf, size_t len) {
  if (buf == NULL || len == 0) return;
  if (c == NULL) {
    snprintf(buf, len, "(none)");
    return;
  }
  snprintf(buf, len, "%s D%g L%g (%d piece%s, %s)", family_name(c->shape), c->diameter, c->length,
           c->npieces, c->npieces == 1 ? "" : "s", c->convex ? "convex" : "non-convex");
}
