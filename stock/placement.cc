/* SPDX-License-Identifier: MPL-2.0 */
/// @file placement.cc
/// @brief Placements: parsing "tx=..,rz=.." and the rigid map (placement.h).
#include "placement.h"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <string>

#include "stock_error.h"

namespace swarf {
namespace {

/// cos and sin of an angle in degrees, exact at whole quarter turns.
void cos_sin_deg(double deg, double &c, double &s) {
  const double q = deg / 90.0;
  if (q == std::floor(q) && std::fabs(q) < 1e15) {
    const long k = ((long)std::fmod(q, 4.0) + 4) % 4;
    const double cs[4] = {1, 0, -1, 0}, sn[4] = {0, 1, 0, -1};
    c = cs[k], s = sn[k];
    return;
  }
  const double r = deg * (M_PI / 180.0);
  c = std::cos(r), s = std::sin(r);
}

void mul(const double a[9], const double b[9], double out[9]) {
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++)
      out[3 * i + j] = a[3 * i] * b[j] + a[3 * i + 1] * b[3 + j] + a[3 * i + 2] * b[6 + j];
}

} // namespace

void Rigid::apply(const double x[3], double y[3]) const {
  for (int i = 0; i < 3; i++)
    y[i] = rot[3 * i] * x[0] + rot[3 * i + 1] * x[1] + rot[3 * i + 2] * x[2] + t[i];
}

void Rigid::invert(const double y[3], double x[3]) const {
  const double d[3] = {y[0] - t[0], y[1] - t[1], y[2] - t[2]};
  for (int i = 0; i < 3; i++)
    x[i] = rot[i] * d[0] + rot[3 + i] * d[1] + rot[6 + i] * d[2];
}

Rigid placement_map(const swarf_stock_placement &p) {
  for (int k = 0; k < 3; k++)
    if (!std::isfinite(p.t[k]) || !std::isfinite(p.r[k]))
      throw Error(SWARF_ERR_ARG, "placement values must be finite");
  double c[3], s[3];
  for (int k = 0; k < 3; k++)
    cos_sin_deg(p.r[k], c[k], s[k]);
  const double rx[9] = {1, 0, 0, 0, c[0], -s[0], 0, s[0], c[0]};
  const double ry[9] = {c[1], 0, s[1], 0, 1, 0, -s[1], 0, c[1]};
  const double rz[9] = {c[2], -s[2], 0, s[2], c[2], 0, 0, 0, 1};
  double zy[9];
  Rigid m;
  mul(rz, ry, zy);
  mul(zy, rx, m.rot);
  for (int k = 0; k < 3; k++)
    m.t[k] = p.t[k];
  return m;
}

bool placement_is_identity(const swarf_stock_placement &p) {
  for (int k = 0; k < 3; k++)
    if (p.t[k] != 0.0 || p.r[k] != 0.0) return false;
  return true;
}

} // namespace swarf

extern "C" swarf_status swarf_stock_placement_parse(const char *spec, swarf_stock_placement *out,
                                                    swarf_error *err) {
  static const char usage[] =
      "write tx=MM,ty=MM,tz=MM,rx=DEG,ry=DEG,rz=DEG (any of them, comma-separated)";
  static const char *keys[6] = {"tx", "ty", "tz", "rx", "ry", "rz"};
  swarf_error_init(err);
  if (out == nullptr) return swarf_error_set(err, SWARF_ERR_ARG, "placement: out is NULL");
  std::memset(out, 0, sizeof *out);
  if (spec == nullptr || *spec == '\0')
    return swarf_error_set(err, SWARF_ERR_ARG, "empty placement; %s", usage);
  int seen = 0;
  const char *s = spec;
  for (;;) {
    int k = 0;
    while (k < 6 && !(std::strncmp(s, keys[k], 2) == 0 && s[2] == '='))
      k++;
    if (k == 6) {
      const std::string item(s, std::strcspn(s, ","));
      return swarf_error_set(err, SWARF_ERR_ARG, "unknown item \"%s\" in \"%s\"; %s", item.c_str(),
                             spec, usage);
    }
    if (seen & (1 << k))
      return swarf_error_set(err, SWARF_ERR_ARG, "%s is given twice in \"%s\"", keys[k], spec);
    seen |= 1 << k;
    s += 3;
    char *end = nullptr;
    errno = 0;
    const double v = std::strtod(s, &end);
    if (end == s || errno == ERANGE || !std::isfinite(v) || (*end != ',' && *end != '\0') ||
        std::fabs(v) > 1e9)
      return swarf_error_set(err, SWARF_ERR_ARG, "%s: bad number in \"%s\"; %s", keys[k], spec,
                             usage);
    (k < 3 ? out->t[k] : out->r[k - 3]) = v;
    if (*end == '\0') return SWARF_OK;
    s = end + 1;
  }
}
