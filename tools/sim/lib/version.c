/* SPDX-License-Identifier: MPL-2.0 */
/* version.c -- the library's version at run time (swarf_version.h). */
#include "swarf_version.h"

const char *swarf_version(void) {
  return SWARF_VERSION_STRING;
}
