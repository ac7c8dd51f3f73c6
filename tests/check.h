/* SPDX-License-Identifier: MPL-2.0 */
/* check.h -- the tests' tiny assertion kit (header only).
 *
 * CHECK(cond, ...) records a failure with a printf-style explanation and goes
 * on; CHECK_NEAR(a, b, tol, what) compares two doubles. check_done() prints
 * "N passed, N failed" and returns the process exit status for main().
 */
#ifndef SWARF_TESTS_CHECK_H
#define SWARF_TESTS_CHECK_H

#include <math.h>
#include <stdio.h>

static int check_passed_, check_failed_;

#define CHECK(cond, ...)                                                                           \
  do {                                                                                             \
    if (cond) {                                                                                    \
      check_passed_++;                                                                             \
    } else {                                                                                       \
      check_failed_++;                                                                             \
      fprintf(stderr, "%s:%d: check failed: %s: ", __FILE__, __LINE__, #cond);                     \
      fprintf(stderr, __VA_ARGS__);                                                                \
      fputc('\n', stderr);                                                                         \
    }                                                                                              \
  } while (0)

#define CHECK_NEAR(a, b, tol, what)                                                                \
  do {                                                                                             \
    double check_a_ = (a), check_b_ = (b);                                                         \
    CHECK(fabs(check_a_ - check_b_) <= (tol), "%s: %.9g vs %.9g (tol %.3g)", (what), check_a_,     \
          check_b_, (double)(tol));                                                                \
  } while (0)

static inline int check_done(void) {
  printf("%d passed, %d failed\n", check_passed_, check_failed_);
  return check_failed_ ? 1 : 0;
}

#endif
