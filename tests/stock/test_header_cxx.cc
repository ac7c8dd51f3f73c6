/* SPDX-License-Identifier: MPL-2.0 */
// test_header_cxx.cc -- stock.h compiles as C++ and links from C++ (extern "C").
#include "stock.h"

#include <cstdio>

int main() {
  swarf_error err = {};
  const double lo[3] = {0, 0, 0}, hi[3] = {1, 1, 1};
  swarf_stock *s = nullptr;
  swarf_stock_new_box(lo, hi, 0.1, 3, &s, &err);
  const bool ok = s != nullptr && swarf_stock_active_voxels(s) > 0;
  swarf_stock_free(s);
  std::printf("%s\n", ok ? "ok" : err.message);
  return ok ? 0 : 1;
}
