/* SPDX-License-Identifier: MPL-2.0 */
/* modbus_tcp.c -- the Modbus TCP status server: one thread, one select()
 * loop, at most SWARF_MB_MAX_CLIENTS clients.
 *
 * Nothing in the loop blocks: sockets are non-blocking, each client has its
 * own frame buffer (MBAP framing is done here, so a client that sends half
 * a frame holds only its own slot), a reply that does not fit in a client's
 * socket buffer drops that client, and clients idle too long are closed.
 *
 * The table (tools/doc/modbus.md): KEEP slots for polite clients
 * plus SPARE more, so that a newcomer always gets in. When all slots are
 * taken, the newcomer replaces, in this order: a misbehaving client (a
 * request refused in the last minute, or a frame left half sent), an
 * unproven one (no request answered yet), an overdue one (silent for longer
 * than three of its own polling periods and 5 s), each the one idle the
 * longest; else the youngest polite client, who is never among the KEEP
 * longest-connected ones. So churn, idle sockets and abusers never reset a
 * polite poller among the KEEP longest-connected clients.
 *
 * The server owns the listening socket, the client sockets and its libmodbus
 * context; it only reads the status it was given, which must outlive it.
 */
#define _GNU_SOURCE /* accept4, pipe2 */
#include <errno.h>
#include <fcntl.h>
#include <netdb.h>
#include <netinet/in.h>
#include <pthread.h>
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/select.h>
#include <sys/socket.h>
#include <unistd.h>

#include "modbus_private.h"

#define KEEP 64  /* polite clients a newcomer never replaces */
#define SPARE 32 /* slots beyond them: the newcomers' way in (~0.3 s at 100 connections/s) */
#define SWARF_MB_MAX_CLIENTS (KEEP + SPARE)
#define IDLE_LIMIT_S 60.0   /* no complete request for this long: closed */
#define PARTIAL_LIMIT_S 5.0 /* a frame left unfinished for this long: closed */
#define PARTIAL_BAD_S 1.0   /* ... for this long: misbehaving */
#define REFUSED_BAD_S 60.0  /* a refused request marks a client for this long */
#define OVERDUE_MIN_S 5.0   /* silent for less is never overdue */
#define OVERDUE_PERIODS 3.0 /* ... nor for less than this many of its periods */

typedef struct {
  int fd; /* -1: free slot */
  int len;
  double since;         /* connection */
  double last;          /* last complete request (or connection) */
  double partial_since; /* first byte of the unfinished frame, 0 if none */
  double good;          /* last request answered normally, 0 if none */
  double period;        /* running mean of the time between answered requests, 0 if unknown */
  double refused;       /* last request refused (exception or no answer), 0 if none */
  uint8_t buf[MODBUS_TCP_MAX_ADU_LENGTH];
} client;

/* Who a newcomer replaces first: lower ranks first. */
enum { RANK_MISBEHAVING, RANK_UNPROVEN, RANK_OVERDUE, RANK_POLITE };

struct swarf_mb_tcp {
  pthread_t thread;
  int listen_fd, wake[2], port;
  atomic_int stop;
  modbus_t *ctx; /* TCP backend for framing replies; its socket is set per request */
  swarf_mb_responder resp;
  client clients[SWARF_MB_MAX_CLIENTS];
  double accept_after; /* out of descriptors: the listener rests until then */
};

/* Out of descriptors (EMFILE, ENFILE) or memory, accept fails while the
 * connection stays queued: select would say "readable" at once, for ever.
 * The listener rests this long instead (a spinning server took a core). */
#define ACCEPT_REST_S 0.2

static void drop(client *c) {
  if (c->fd >= 0) close(c->fd);
  c->fd = -1;
  c->len = 0;
  c->partial_since = 0;
}

/* A new client in slot c, connected at now. */
static void client_init(client *c, int fd, double now) {
  c->fd = fd;
  c->len = 0;
  c->since = c->last = now;
  c->partial_since = c->good = c->period = c->refused = 0;
}

/* Note one complete request at now, answered normally or refused. */
static void client_note(client *c, int refused, double now) {
  c->last = now;
  c->partial_since = 0;
  if (refused) {
    c->refused = now;
    return;
  }
  if (c->good > 0) /* a mean over the last ~4 periods */
    c->period = c->period > 0 ? 0.75 * c->period + 0.25 * (now - c->good) : now - c->good;
  c->good = now;
}

static int client_rank(const client *c, double now) {
  double overdue = OVERDUE_PERIODS * c->period;
  if ((c->refused > 0 && now - c->refused < REFUSED_BAD_S) ||
      (c->partial_since > 0 && now - c->partial_since >= PARTIAL_BAD_S))
    return RANK_MISBEHAVING;
  if (c->good == 0) return RANK_UNPROVEN;
  if (now - c->good > (overdue > OVERDUE_MIN_S ? overdue : OVERDUE_MIN_S)) return RANK_OVERDUE;
  return RANK_POLITE;
}

/* Total length of the first frame in c's buffer, 0 if incomplete, -1 if it
 * cannot be a Modbus TCP frame (a TCP stream cannot resync: drop it). */
static int frame_length(const client *c) {
  int proto, n;
  if (c->len < 7) return 0;
  proto = c->buf[2] << 8 | c->buf[3];
  n = c->buf[4] << 8 | c->buf[5];
  if (proto != 0 || n < 2 || n > MODBUS_TCP_MAX_ADU_LENGTH - 6) return -1;
  return c->len >= 6 + n ? 6 + n : 0;
}

static void serve_frames(struct swarf_mb_tcp *t, client *c, double now) {
  int n;
  while (c->fd >= 0 && (n = frame_length(c)) != 0) {
    modbus_set_socket(t->ctx, c->fd);
    if (n < 0 || swarf_mb_respond(&t->resp, t->ctx, c->buf, n) < 0) {
      drop(c);
      return;
    }
    memmove(c->buf, c->buf + n, (size_t)(c->len - n));
    c->len -= n;
    client_note(c, t->resp.refused, now);
  }
  if (c->fd >= 0 && c->len > 0 && c->partial_since == 0) c->partial_since = now;
}

static void on_readable(struct swarf_mb_tcp *t, client *c, double now) {
  ssize_t got = recv(c->fd, c->buf + c->len, sizeof c->buf - (size_t)c->len, 0);
  if (got == 0 || (got < 0 && errno != EAGAIN && errno != EWOULDBLOCK && errno != EINTR)) {
    drop(c);
    return;
  }
  if (got > 0) c->len += (int)got;
  serve_frames(t, c, now);
}

/* Should a newcomer replace a (of rank ra) rather than b (of rank rb)? The
 * lower rank; in a rank, the one idle the longest, but among polite clients
 * the youngest (so the KEEP longest-connected ones stay). */
static int replace_first(const client *a, int ra, const client *b, int rb) {
  if (ra != rb) return ra < rb;
  return ra == RANK_POLITE ? a->since > b->since : a->last < b->last;
}

/* A free slot, or the slot of the client a newcomer replaces (closed). */
static client *free_slot(struct swarf_mb_tcp *t, double now) {
  client *victim = NULL;
  int vrank = 0;
  for (int i = 0; i < SWARF_MB_MAX_CLIENTS; i++) {
    client *c = &t->clients[i];
    int r;
    if (c->fd < 0) return c;
    r = client_rank(c, now);
    if (victim == NULL || replace_first(c, r, victim, vrank)) victim = c, vrank = r;
  }
  drop(victim);
  return victim;
}

static void on_accept(struct swarf_mb_tcp *t, double now) {
  int fd = accept4(t->listen_fd, NULL, NULL, SOCK_NONBLOCK | SOCK_CLOEXEC);
  client *c;
  if (fd < 0) {
    if (errno == EMFILE || errno == ENFILE || errno == ENOBUFS || errno == ENOMEM)
      t->accept_after = now + ACCEPT_REST_S;
    return;
  }
  if (fd >= FD_SETSIZE || (c = free_slot(t, now)) == NULL) {
    close(fd);
    return;
  }
  client_init(c, fd, now);
}

static void close_stale(struct swarf_mb_tcp *t, double now) {
  for (int i = 0; i < SWARF_MB_MAX_CLIENTS; i++) {
    client *c = &t->clients[i];
    if (c->fd < 0) continue;
    if (now - c->last > IDLE_LIMIT_S ||
        (c->partial_since > 0 && now - c->partial_since > PARTIAL_LIMIT_S))
      drop(c);
  }
}

static int fill_set(struct swarf_mb_tcp *t, fd_set *rd, double now) {
  int top = t->listen_fd > t->wake[0] ? t->listen_fd : t->wake[0];
  FD_ZERO(rd);
  if (now >= t->accept_after) FD_SET(t->listen_fd, rd);
  FD_SET(t->wake[0], rd);
  for (int i = 0; i < SWARF_MB_MAX_CLIENTS; i++) {
    if (t->clients[i].fd < 0) continue;
    FD_SET(t->clients[i].fd, rd);
    if (t->clients[i].fd > top) top = t->clients[i].fd;
  }
  return top;
}

static void *loop(void *arg) {
  struct swarf_mb_tcp *t = arg;
  while (!atomic_load(&t->stop)) {
    fd_set rd;
    struct timeval tv = {0, 250000};
    int top = fill_set(t, &rd, swarf_job_now());
    int n = select(top + 1, &rd, NULL, NULL, &tv);
    double now = swarf_job_now();
    if (n < 0 && errno != EINTR) break;
    if (n > 0) {
      for (int i = 0; i < SWARF_MB_MAX_CLIENTS; i++)
        if (t->clients[i].fd >= 0 && FD_ISSET(t->clients[i].fd, &rd))
          on_readable(t, &t->clients[i], now);
      if (FD_ISSET(t->listen_fd, &rd)) on_accept(t, now);
    }
    close_stale(t, now);
  }
  return NULL;
}

/* Bind and listen on e's host and port; fills t->listen_fd and t->port. */
static swarf_status listen_on(struct swarf_mb_tcp *t, const swarf_mb_endpoint *e,
                              swarf_error *err) {
  struct addrinfo hints = {0}, *ai = NULL;
  struct sockaddr_storage ss;
  socklen_t sl = sizeof ss;
  int one = 1, rc;
  hints.ai_family = AF_UNSPEC;
  hints.ai_socktype = SOCK_STREAM;
  hints.ai_flags = AI_PASSIVE;
  if ((rc = getaddrinfo(e->host, e->port, &hints, &ai)) != 0)
    return swarf_error_set(err, SWARF_ERR_ARG, "--modbus: cannot resolve \"%s\": %s", e->host,
                           gai_strerror(rc));
  t->listen_fd = socket(ai->ai_family, ai->ai_socktype | SOCK_NONBLOCK | SOCK_CLOEXEC, 0);
  if (t->listen_fd >= 0) setsockopt(t->listen_fd, SOL_SOCKET, SO_REUSEADDR, &one, sizeof one);
  rc = t->listen_fd < 0 || bind(t->listen_fd, ai->ai_addr, ai->ai_addrlen) ||
       listen(t->listen_fd, SOMAXCONN) || getsockname(t->listen_fd, (struct sockaddr *)&ss, &sl);
  freeaddrinfo(ai);
  if (rc)
    return swarf_error_set(
        err, SWARF_ERR_ARG,
        "--modbus: cannot listen on %s:%s: %s (choose another port, or 0 for a free one)", e->host,
        e->port, strerror(errno));
  t->port = ntohs(ss.ss_family == AF_INET6 ? ((struct sockaddr_in6 *)&ss)->sin6_port
                                           : ((struct sockaddr_in *)&ss)->sin_port);
  return SWARF_OK;
}

swarf_status swarf_mb_tcp_new(const swarf_mb_endpoint *e, swarf_job *status, swarf_mb_tcp **out,
                              swarf_error *err) {
  struct swarf_mb_tcp *t;
  swarf_status st;
  if (out == NULL || e == NULL || status == NULL || e->kind != SWARF_MB_TCP)
    return swarf_error_set(err, SWARF_ERR_ARG, "swarf_mb_tcp_new: no TCP endpoint");
  *out = NULL;
  if ((t = calloc(1, sizeof *t)) == NULL)
    return swarf_error_set(err, SWARF_ERR_MEMORY, "out of memory");
  t->listen_fd = t->wake[0] = t->wake[1] = -1;
  for (int i = 0; i < SWARF_MB_MAX_CLIENTS; i++)
    t->clients[i].fd = -1;
  atomic_init(&t->stop, 0);
  if ((st = listen_on(t, e, err)) != SWARF_OK) goto err;
  t->ctx = modbus_new_tcp("127.0.0.1", t->port);
  if (t->ctx) modbus_set_response_timeout(t->ctx, 0, 1); /* libmodbus sleeps it on errors */
  if (t->ctx == NULL || swarf_mb_responder_init(&t->resp, status, e->unit, 1) ||
      pipe2(t->wake, O_CLOEXEC) || pthread_create(&t->thread, NULL, loop, t)) {
    st = swarf_error_set(err, SWARF_ERR_INTERNAL, "--modbus: cannot start the server: %s",
                         strerror(errno));
    goto err;
  }
  *out = t;
  return SWARF_OK;
err:
  if (t->ctx) modbus_free(t->ctx);
  swarf_mb_responder_clear(&t->resp);
  if (t->listen_fd >= 0) close(t->listen_fd);
  if (t->wake[0] >= 0) close(t->wake[0]), close(t->wake[1]);
  free(t);
  return st;
}

int swarf_mb_tcp_port(const swarf_mb_tcp *t) {
  return t ? t->port : -1;
}

void swarf_mb_tcp_free(swarf_mb_tcp *t) {
  if (t == NULL) return;
  atomic_store(&t->stop, 1);
  if (write(t->wake[1], "x", 1) < 0) { /* select wakes within 0.25 s anyway */
  }
  pthread_join(t->thread, NULL);
  for (int i = 0; i < SWARF_MB_MAX_CLIENTS; i++)
    drop(&t->clients[i]);
  modbus_set_socket(t->ctx, -1);
  modbus_free(t->ctx);
  swarf_mb_responder_clear(&t->resp);
  close(t->listen_fd);
  close(t->wake[0]);
  close(t->wake[1]);
  free(t);
}
