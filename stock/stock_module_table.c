/* SPDX-License-Identifier: MPL-2.0 */
/* stock_module_table.c -- the stock module's one export: its function table
 * (stock_module.h), built into swarf_stock-VERSION.so only. */
#include "stock_module.h"

SWARF_API extern const swarf_stock_module swarf_stock_module_table;

const swarf_stock_module swarf_stock_module_table = {
    sizeof(swarf_stock_module),
    SWARF_STOCK_MODULE_VERSION,
#define STATUS(name, params, args) name,
#define VOID(name, params, args) name,
#define VALUE(type, name, params, args, fallback) name,
#include "stock_api.def"
#undef STATUS
#undef VOID
#undef VALUE
};
