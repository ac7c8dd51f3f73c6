// test_header_cxx.cc -- stock.h compiles as C++ and links from C++ (extern "C").
#include "stock.h"

#include <cstdio>

int main() {
  char msg[128];
  const double lo[3] = {0, 0, 0}, hi[3] = {1, 1, 1};
  swarf_stock *s = swarf_stock_new_box(lo, hi, 0.1, 3, msg, sizeof msg);
  const bool ok = s != nullptr && swarf_stock_active_voxels(s) > 0;
  swarf_stock_free(s);
  std::printf("%s\n", ok ? "ok" : msg);
  return ok ? 0 : 1;
}
