/* SPDX-License-Identifier: MPL-2.0 */
/* fuzz_modbus.c -- the fuzz entry for the Modbus request handler
 * (tools/modbus_request.c, and libmodbus's modbus_reply behind it).
 *
 * The first input byte picks the backend (even: TCP, odd: RTU); the rest is
 * cut into frames, each preceded by its length byte, and every frame is
 * answered on a socket pair as the servers would. Checks: the handler
 * returns -1, 0 or the bytes it sent; every reply is well formed (TCP: the
 * request's transaction id, a length field that matches, the request's
 * function code or it | 0x80 with a known exception; RTU: at most 256
 * bytes, never an answer to a broadcast). The status owns no job: its
 * snapshot is whatever the input's commands made of it.
 */
#include <fcntl.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <unistd.h>

#include "modbus_private.h"

static swarf_job *status;
static modbus_t *tcp, *rtu;
static swarf_mb_responder rtcp, rrtu;
static int fds[2];

static void fail(const char *why, const uint8_t *req, int len, const uint8_t *rsp, int n) {
  fprintf(stderr, "fuzz_modbus: %s\nrequest:", why);
  for (int i = 0; i < len; i++)
    fprintf(stderr, " %02x", req[i]);
  fprintf(stderr, "\nreply:");
  for (int i = 0; i < n; i++)
    fprintf(stderr, " %02x", rsp[i]);
  fprintf(stderr, "\n");
  abort();
}

static void setup(void) {
  status = swarf_job_new("fuzz.ngc");
  swarf_job_set_commands(status, 1);
  tcp = modbus_new_tcp("127.0.0.1", 502);
  rtu = modbus_new_rtu("/dev/null", 19200, 'N', 8, 1);
  if (!status || !tcp || !rtu || socketpair(AF_UNIX, SOCK_STREAM, 0, fds) ||
      swarf_mb_responder_init(&rtcp, status, 1, 1) || swarf_mb_responder_init(&rrtu, status, 1, 0))
    abort();
  fcntl(fds[0], F_SETFL, O_NONBLOCK);
  fcntl(fds[1], F_SETFL, O_NONBLOCK);
  modbus_set_slave(rtu, 1);
  modbus_set_response_timeout(tcp, 0, 1); /* as the servers do */
  modbus_set_response_timeout(rtu, 0, 1);
  modbus_set_socket(tcp, fds[0]);
  modbus_set_socket(rtu, fds[0]);
}

static void check_reply(int is_tcp, const uint8_t *req, int len, const uint8_t *rsp, int n) {
  if (n == 0) return;
  if (!is_tcp) {
    if (n > MODBUS_RTU_MAX_ADU_LENGTH || req[0] == 0) fail("RTU reply", req, len, rsp, n);
    return;
  }
  if (n < 9 || rsp[0] != req[0] || rsp[1] != req[1] || (rsp[4] << 8 | rsp[5]) != n - 6)
    fail("TCP reply header", req, len, rsp, n);
  if (rsp[7] != req[7] && (rsp[7] != (req[7] | 0x80) || rsp[8] < 1 || rsp[8] > 0x0B))
    fail("TCP reply function", req, len, rsp, n);
}

static void one_frame(int is_tcp, const uint8_t *req, int len) {
  uint8_t rsp[1024];
  int rc = swarf_mb_respond(is_tcp ? &rtcp : &rrtu, is_tcp ? tcp : rtu, req, len);
  ssize_t n = recv(fds[1], rsp, sizeof rsp, 0);
  if (n < 0) n = 0;
  if ((rc > 0 && rc != n) || (rc <= 0 && n != 0))
    fail("sent/returned mismatch", req, len, rsp, (int)n);
  check_reply(is_tcp, req, len, rsp, (int)n);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  uint8_t frame[MODBUS_TCP_MAX_ADU_LENGTH];
  size_t at = 1;
  if (status == NULL) setup();
  if (size < 2) return 0;
  while (at < size) {
    size_t len = data[at++];
    if (len > size - at) len = size - at;
    if (len > sizeof frame) len = sizeof frame;
    memset(frame, 0, sizeof frame);
    memcpy(frame, data + at, len);
    at += len;
    if ((data[0] & 1) == 0 && len < 8) continue; /* the TCP server frames at least 8 bytes */
    if ((data[0] & 1) == 0) { /* ... with protocol 0 and a length field that fits */
      frame[2] = frame[3] = 0;
      frame[4] = (uint8_t)((len - 6) >> 8);
      frame[5] = (uint8_t)(len - 6);
    }
    if ((data[0] & 1) == 1 && len < 4) continue; /* libmodbus RTU: unit, function, CRC */
    one_frame((data[0] & 1) == 0, frame, (int)len);
  }
  if (swarf_job_abort_requested(status) || swarf_job_pause_requested(status))
    swarf_job_command_post(status, SWARF_JOB_CMD_RESUME);
  return 0;
}
