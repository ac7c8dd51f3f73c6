/* SPDX-License-Identifier: MPL-2.0 */
// consumer_cxx.cc -- every public header of an installed libswarf compiles as
// C++ (-std=c++17 -pedantic -Wall -Wextra -Werror) and links from C++ (the
// declarations are extern "C").
#include <swarf/envelope_exact.h>
#include <swarf/swarf.h>

#include <cstdio>
#include <cstring>

int main() {
  swarf_sim_config cfg;
  swarf_sim_config_init(&cfg);
  swarf_error err;
  swarf_error_init(&err);
  swarf_sim_stock_spec stock;
  const bool parsed = swarf_sim_parse_stock("box:0,0,-1,1,1,0", &stock, &err) == SWARF_OK;
  swarf_qr q;
  swarf_qr_init(&q);
  const bool exact = swarf_qr_is_zero(&q) != 0;
  swarf_qr_clear(&q);
  const bool ok = parsed && exact && cfg.voxel > 0.0 &&
                  std::strcmp(swarf_status_name(SWARF_ERR_SYNTAX), "SWARF_ERR_SYNTAX") == 0 &&
                  std::strcmp(swarf_version(), SWARF_VERSION_STRING) == 0;
  std::printf("consumer_cxx: %s\n", ok ? "ok" : "FAILED");
  return ok ? 0 : 1;
}
