/* SPDX-License-Identifier: MPL-2.0 */
/* modbus_request.c -- one Modbus request in, one reply or exception out.
 *
 * Shared by the TCP and RTU servers. Reads (FC 01-04, 17) are answered by
 * libmodbus from a mapping refreshed from the status snapshot just before;
 * this file decides everything libmodbus would not: the unit filter, PDUs
 * whose length does not match their function (exception 03), and writes
 * (exception 01 unless --modbus-commands; then only the command register
 * takes a command, exception 02 elsewhere, 03 for a value that is not one);
 * function codes from 0x80 up (exception codes, not functions) are dropped.
 * Exceptions for unknown functions and bad counts are sent from here:
 * libmodbus's own path for them sleeps the response timeout and flushes.
 * The responder records whether the last request was refused (an exception
 * or no answer): the TCP server ranks its clients by it. The responder owns
 * its mapping; the caller owns ctx and the request.
 */
#include "modbus_private.h"

int swarf_mb_responder_init(swarf_mb_responder *r, swarf_job *status, int unit, int tcp) {
  if (r == NULL || status == NULL) return -1;
  r->status = status;
  r->unit = unit;
  r->tcp = tcp;
  r->refused = 0;
  r->map = modbus_mapping_new_start_address(0, 0, 0, SWARF_MB_NBITS, 0, SWARF_MB_NREGS + 1, 0,
                                            SWARF_MB_NREGS);
  return r->map ? 0 : -1;
}

void swarf_mb_responder_clear(swarf_mb_responder *r) {
  if (r == NULL) return;
  modbus_mapping_free(r->map);
  r->map = NULL;
}

/* Does the PDU have the length its function code implies? */
static int pdu_ok(const uint8_t *pdu, int n) {
  switch (pdu[0]) {
  case MODBUS_FC_READ_COILS:
  case MODBUS_FC_READ_DISCRETE_INPUTS:
  case MODBUS_FC_READ_HOLDING_REGISTERS:
  case MODBUS_FC_READ_INPUT_REGISTERS:
  case MODBUS_FC_WRITE_SINGLE_COIL:
  case MODBUS_FC_WRITE_SINGLE_REGISTER:
    return n == 5;
  case MODBUS_FC_WRITE_MULTIPLE_COILS:
  case MODBUS_FC_WRITE_MULTIPLE_REGISTERS:
    return n >= 6 && n == 6 + pdu[5];
  case MODBUS_FC_REPORT_SLAVE_ID:
    return n == 1;
  case MODBUS_FC_MASK_WRITE_REGISTER:
    return n == 7;
  case MODBUS_FC_WRITE_AND_READ_REGISTERS:
    return n >= 10 && n == 10 + pdu[9];
  default:
    return 1;
  }
}

static int known(int fc) {
  return (fc >= MODBUS_FC_READ_COILS && fc <= MODBUS_FC_WRITE_SINGLE_REGISTER) ||
         fc == MODBUS_FC_WRITE_MULTIPLE_COILS || fc == MODBUS_FC_WRITE_MULTIPLE_REGISTERS ||
         fc == MODBUS_FC_REPORT_SLAVE_ID || fc == MODBUS_FC_MASK_WRITE_REGISTER ||
         fc == MODBUS_FC_WRITE_AND_READ_REGISTERS;
}

/* Counts within the protocol's limits (libmodbus would answer these
 * exceptions itself, but after sleeping its response timeout). */
static int counts_ok(const uint8_t *pdu) {
  int nb = pdu[3] << 8 | pdu[4], nw = pdu[7] << 8 | pdu[8];
  switch (pdu[0]) {
  case MODBUS_FC_READ_COILS:
  case MODBUS_FC_READ_DISCRETE_INPUTS:
    return nb >= 1 && nb <= MODBUS_MAX_READ_BITS;
  case MODBUS_FC_READ_HOLDING_REGISTERS:
  case MODBUS_FC_READ_INPUT_REGISTERS:
    return nb >= 1 && nb <= MODBUS_MAX_READ_REGISTERS;
  case MODBUS_FC_WRITE_MULTIPLE_COILS:
    return nb >= 1 && nb <= MODBUS_MAX_WRITE_BITS && pdu[5] == (nb + 7) / 8;
  case MODBUS_FC_WRITE_MULTIPLE_REGISTERS:
    return nb >= 1 && nb <= MODBUS_MAX_WRITE_REGISTERS && pdu[5] == 2 * nb;
  case MODBUS_FC_WRITE_AND_READ_REGISTERS:
    return nb >= 1 && nb <= MODBUS_MAX_WR_READ_REGISTERS && nw >= 1 &&
           nw <= MODBUS_MAX_WR_WRITE_REGISTERS && pdu[9] == 2 * nw;
  default:
    return 1;
  }
}

static int is_write(int fc) {
  return fc == MODBUS_FC_WRITE_SINGLE_COIL || fc == MODBUS_FC_WRITE_SINGLE_REGISTER ||
         fc == MODBUS_FC_WRITE_MULTIPLE_COILS || fc == MODBUS_FC_WRITE_MULTIPLE_REGISTERS ||
         fc == MODBUS_FC_MASK_WRITE_REGISTER || fc == MODBUS_FC_WRITE_AND_READ_REGISTERS;
}

/* A write with commands on: 0 if it posted a command, else the exception. */
static int command_write(swarf_mb_responder *r, const uint8_t *pdu) {
  int addr = pdu[1] << 8 | pdu[2], value;
  if (pdu[0] == MODBUS_FC_WRITE_SINGLE_REGISTER) {
    value = pdu[3] << 8 | pdu[4];
  } else if (pdu[0] == MODBUS_FC_WRITE_MULTIPLE_REGISTERS) {
    if ((pdu[3] << 8 | pdu[4]) != 1 || pdu[5] != 2) return MODBUS_EXCEPTION_ILLEGAL_DATA_ADDRESS;
    value = pdu[6] << 8 | pdu[7];
  } else {
    return pdu[0] == MODBUS_FC_MASK_WRITE_REGISTER || pdu[0] == MODBUS_FC_WRITE_AND_READ_REGISTERS
               ? MODBUS_EXCEPTION_ILLEGAL_FUNCTION
               : MODBUS_EXCEPTION_ILLEGAL_DATA_ADDRESS;
  }
  if (addr != SWARF_MB_CMD_REG) return MODBUS_EXCEPTION_ILLEGAL_DATA_ADDRESS;
  return swarf_job_command_post(r->status, value) ? MODBUS_EXCEPTION_ILLEGAL_DATA_VALUE : 0;
}

static void refresh(swarf_mb_responder *r) {
  swarf_job_snapshot s;
  swarf_job_read(r->status, &s);
  swarf_mb_map_registers(&s, swarf_job_now(), r->map->tab_input_registers);
  for (int i = 0; i < SWARF_MB_NREGS; i++)
    r->map->tab_registers[i] = r->map->tab_input_registers[i];
  r->map->tab_registers[SWARF_MB_CMD_REG] = (uint16_t)s.last_command;
  swarf_mb_map_bits(&s, r->map->tab_input_bits);
}

/* Answer req with a normal reply; r->refused tells whether libmodbus
 * answered an exception itself (an address outside the map): an exception is
 * the header, function and code (+ CRC), every normal reply is longer. */
static int reply(swarf_mb_responder *r, modbus_t *ctx, const uint8_t *req, int len, int h) {
  int rc;
  refresh(r);
  rc = modbus_reply(ctx, req, len, r->map);
  r->refused = rc == h + 2 + (r->tcp ? 0 : 2);
  return rc;
}

int swarf_mb_respond(swarf_mb_responder *r, modbus_t *ctx, const uint8_t *req, int len) {
  int h = modbus_get_header_length(ctx), n, unit, ex = 0;
  swarf_job_snapshot s;
  if (r == NULL || ctx == NULL || req == NULL || h < 1) return -1;
  r->refused = 1;                 /* until a normal reply is sent */
  n = len - h - (r->tcp ? 0 : 2); /* RTU frames end with a CRC */
  if (n < 1) return 0;
  unit = req[h - 1];
  if (req[h] & 0x80) return 0; /* not a function: libmodbus would answer it as FC & 0x7F */
  if (!r->tcp && unit == MODBUS_BROADCAST_ADDRESS) return 0; /* broadcasts are ignored */
  if (r->tcp && unit != r->unit && unit != 0 && unit != MODBUS_TCP_SLAVE)
    return modbus_reply_exception(ctx, req, MODBUS_EXCEPTION_GATEWAY_TARGET);
  if (!known(req[h])) return modbus_reply_exception(ctx, req, MODBUS_EXCEPTION_ILLEGAL_FUNCTION);
  if (!pdu_ok(req + h, n) || !counts_ok(req + h))
    return modbus_reply_exception(ctx, req, MODBUS_EXCEPTION_ILLEGAL_DATA_VALUE);
  if (is_write(req[h])) {
    swarf_job_read(r->status, &s);
    ex = s.commands ? command_write(r, req + h) : MODBUS_EXCEPTION_ILLEGAL_FUNCTION;
  }
  if (ex) return modbus_reply_exception(ctx, req, (unsigned)ex);
  return reply(r, ctx, req, len, h);
}
