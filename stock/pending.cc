/// @file pending.cc
/// @brief Entry points of stock.h whose implementation is on its way (issue 11);
/// each returns SWARF_ERR_INTERNAL "not implemented yet". Removed as they land.
#include "stock.h"

#include <cstdio>

namespace {
swarf_status pending(swarf_error *err, const char *what) {
  return swarf_error_set(err, SWARF_ERR_INTERNAL, "%s: not implemented yet", what);
}
}  // namespace

extern "C" {

swarf_status swarf_stock_placement_parse(const char *, swarf_stock_placement *, swarf_error *err) {
  return pending(err, "swarf_stock_placement_parse");
}
swarf_status swarf_stock_read_stl(const char *, const swarf_stock_placement *, double, int,
                                  swarf_stock **out, swarf_error *err) {
  if (out) *out = nullptr;
  return pending(err, "swarf_stock_read_stl");
}
swarf_status swarf_stock_read_vdb(const char *, const swarf_stock_placement *, double, int,
                                  swarf_stock **out, swarf_error *err) {
  if (out) *out = nullptr;
  return pending(err, "swarf_stock_read_vdb");
}
swarf_status swarf_stock_place(const swarf_stock *, const swarf_stock_placement *,
                               swarf_stock **out, swarf_error *err) {
  if (out) *out = nullptr;
  return pending(err, "swarf_stock_place");
}
swarf_status swarf_stock_rebuild(const swarf_stock *, double, int, swarf_stock **out,
                                 swarf_error *err) {
  if (out) *out = nullptr;
  return pending(err, "swarf_stock_rebuild");
}
swarf_status swarf_stock_read_design(const char *, double, swarf_stock **out, swarf_error *err) {
  if (out) *out = nullptr;
  return pending(err, "swarf_stock_read_design");
}
swarf_status swarf_stock_check_design(const swarf_stock *, const swarf_stock *, swarf_error *err) {
  return pending(err, "swarf_stock_check_design");
}
swarf_status swarf_stock_compare(const swarf_stock *, const swarf_stock *, const swarf_stock *,
                                 double, swarf_stock_deviation *, swarf_error *err) {
  return pending(err, "swarf_stock_compare");
}
swarf_status swarf_stock_gouge(const swarf_stock *, const swarf_stock *, const swarf_stock_cut *,
                               double, double *, double *, swarf_error *err) {
  return pending(err, "swarf_stock_gouge");
}
swarf_status swarf_stock_remove_batch_measured(swarf_stock *, const swarf_stock_cut *, size_t,
                                               const swarf_stock *, double,
                                               swarf_stock_cut_effect *, swarf_error *err) {
  return pending(err, "swarf_stock_remove_batch_measured");
}
swarf_status swarf_stock_view_parse(const char *, swarf_stock_view *, swarf_error *err) {
  return pending(err, "swarf_stock_view_parse");
}
swarf_status swarf_stock_write_image(const swarf_stock *, const char *, const swarf_stock_output *,
                                     swarf_error *err) {
  return pending(err, "swarf_stock_write_image");
}
swarf_status swarf_stock_write_mesh(const swarf_stock *, const char *, const swarf_stock_output *,
                                    size_t *, swarf_error *err) {
  return pending(err, "swarf_stock_write_mesh");
}
}
