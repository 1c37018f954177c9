#include "drivers/common/drv_port.h"

#include <errno.h>
#include <fcntl.h>
#include <netdb.h>
#include <poll.h>
#include <stdio.h>
#include <string.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <termios.h>
#include <unistd.h>

#define FIRST_BACKOFF_MS 100
#define CONNECT_TIMEOUT_MS 5000

static const struct {
    int baud;
    speed_t speed;
} bauds[] = {
    {1200, B1200},     {2400, B2400},     {4800, B4800},     {9600, B9600},       {19200, B19200},
    {38400, B38400},   {57600, B57600},   {115200, B115200}, {230400, B230400},   {460800, B460800},
    {921600, B921600},
};

static int speed_of(int baud, speed_t *out)
{
    for (size_t i = 0; i < sizeof bauds / sizeof bauds[0]; i++)
        if (bauds[i].baud == baud) {
            *out = bauds[i].speed;
            return 1;
        }
    return 0;
}

int drv_port_baud_ok(int baud)
{
    speed_t s;
    return speed_of(baud, &s);
}

static void init_common(drv_port *p, const char *log_prefix)
{
    memset(p, 0, sizeof *p);
    p->fd = -1;
    p->state = DRV_PORT_CLOSED;
    p->backoff_ms = FIRST_BACKOFF_MS;
    p->log_prefix = log_prefix;
}

void drv_port_serial(drv_port *p, const char *path, int baud, const char *log_prefix)
{
    init_common(p, log_prefix);
    snprintf(p->path, sizeof p->path, "%s", path);
    p->baud = baud;
    snprintf(p->name, sizeof p->name, "%s@%d", path, baud);
}

int drv_port_tcp(drv_port *p, const char *host_port, const char *log_prefix, char *err, size_t errlen)
{
    init_common(p, log_prefix);
    p->is_tcp = 1;
    /* HOST:PORT, or [v6addr]:PORT */
    const char *colon = strrchr(host_port, ':');
    const char *h = host_port;
    size_t hlen = colon ? (size_t)(colon - host_port) : 0;
    if (hlen >= 2 && h[0] == '[' && h[hlen - 1] == ']') {
        h++;
        hlen -= 2;
    }
    if (!colon || hlen == 0 || hlen >= sizeof p->host || !colon[1] || strlen(colon + 1) >= sizeof p->service) {
        snprintf(err, errlen, "--tcp wants HOST:PORT, not '%s'", host_port);
        return -1;
    }
    for (const char *c = colon + 1; *c; c++)
        if (*c < '0' || *c > '9') {
            snprintf(err, errlen, "--tcp wants HOST:PORT with a numeric port, not '%s'", host_port);
            return -1;
        }
    memcpy(p->host, h, hlen);
    p->host[hlen] = '\0';
    snprintf(p->service, sizeof p->service, "%s", colon + 1);
    snprintf(p->name, sizeof p->name, "tcp:%s", host_port);
    return 0;
}

/* The port failed or vanished: close it and schedule the next attempt. A
 * failure is logged when it differs from the last one logged, so a device
 * unplugged for an hour gives one line, not one per retry. */
static void fail(drv_port *p, int64_t now_ms, const char *what, int err)
{
    snprintf(p->last_error, sizeof p->last_error, "%s %s: %s", what, p->name, err ? strerror(err) : "end of file");
    if (strcmp(p->last_error, p->logged_error) != 0) {
        fprintf(stderr, "%s: %s (retrying every %d ms at most)\n", p->log_prefix, p->last_error,
                DRV_PORT_MAX_BACKOFF_MS);
        snprintf(p->logged_error, sizeof p->logged_error, "%s", p->last_error);
    }
    if (p->fd >= 0)
        close(p->fd);
    p->fd = -1;
    p->state = DRV_PORT_CLOSED;
    p->retry_at_ms = now_ms + p->backoff_ms;
    p->backoff_ms = p->backoff_ms * 2 > DRV_PORT_MAX_BACKOFF_MS ? DRV_PORT_MAX_BACKOFF_MS : p->backoff_ms * 2;
}

static void opened(drv_port *p)
{
    p->state = DRV_PORT_OPEN;
    if (p->was_open)
        p->reopens++;
    fprintf(stderr, "%s: %s %s\n", p->log_prefix, p->was_open ? "reopened" : "opened", p->name);
    p->was_open = 1;
    p->logged_error[0] = '\0';
}

/* A regular file is a recording (read-only: a protocol's commands must not
 * land in it), a FIFO a line without settings; neither has termios. */
static void open_not_a_line(drv_port *p, int64_t now_ms, const struct stat *st)
{
    int regular = S_ISREG(st->st_mode);
    int fd = open(p->path, (regular ? O_RDONLY : O_RDWR) | O_NONBLOCK | O_CLOEXEC);
    if (fd < 0) {
        fail(p, now_ms, "cannot open", errno);
        return;
    }
    p->fd = fd;
    p->is_file = regular;
    fprintf(stderr, "%s: %s is %s\n", p->log_prefix, p->path,
            regular ? "a file: read once as a recording, to its end, and nothing written to it"
                    : "a FIFO: read as a line without settings");
    opened(p);
}

static void open_serial(drv_port *p, int64_t now_ms)
{
    struct stat st;
    if (stat(p->path, &st) == 0 && (S_ISREG(st.st_mode) || S_ISFIFO(st.st_mode))) {
        open_not_a_line(p, now_ms, &st);
        return;
    }
    int fd = open(p->path, O_RDWR | O_NOCTTY | O_NONBLOCK | O_CLOEXEC);
    if (fd < 0) {
        fail(p, now_ms, "cannot open", errno);
        return;
    }
    p->fd = fd;
    struct termios t;
    speed_t speed = B9600;
    speed_of(p->baud, &speed); /* checked when the flags were read */
    if (tcgetattr(fd, &t) < 0) {
        fail(p, now_ms, "not a serial line (tcgetattr):", errno);
        return;
    }
    /* raw: no echo, no line editing, no CR/LF translation, 8N1, no flow
     * control, reads return what is there (VMIN 0, VTIME 0) */
    cfmakeraw(&t);
    t.c_cflag |= CLOCAL | CREAD;
    t.c_cflag &= ~(tcflag_t)(CSTOPB | PARENB | CRTSCTS);
    t.c_iflag &= ~(tcflag_t)(IXON | IXOFF | IXANY);
    t.c_cc[VMIN] = 0;
    t.c_cc[VTIME] = 0;
    if (cfsetispeed(&t, speed) < 0 || cfsetospeed(&t, speed) < 0 || tcsetattr(fd, TCSANOW, &t) < 0) {
        fail(p, now_ms, "cannot set raw mode and baud on", errno);
        return;
    }
    opened(p);
}

static void open_tcp(drv_port *p, int64_t now_ms)
{
    struct addrinfo hints = {0}, *ai = NULL;
    hints.ai_family = AF_UNSPEC;
    hints.ai_socktype = SOCK_STREAM;
    /* a name is resolved here, blocking: use an address on a vehicle */
    int g = getaddrinfo(p->host, p->service, &hints, &ai);
    if (g != 0) {
        (void)g; /* gai_strerror's text is not errno's: say it as "host unreachable" */
        fail(p, now_ms, "cannot resolve", EHOSTUNREACH);
        return;
    }
    int fd = socket(ai->ai_family, ai->ai_socktype | SOCK_NONBLOCK | SOCK_CLOEXEC, ai->ai_protocol);
    if (fd < 0) {
        freeaddrinfo(ai);
        fail(p, now_ms, "cannot create a socket for", errno);
        return;
    }
    p->fd = fd;
    int r = connect(fd, ai->ai_addr, ai->ai_addrlen);
    int e = errno;
    freeaddrinfo(ai);
    if (r == 0) {
        opened(p);
    } else if (e == EINPROGRESS) {
        p->state = DRV_PORT_CONNECTING;
        p->retry_at_ms = now_ms + CONNECT_TIMEOUT_MS; /* the connect's deadline */
    } else {
        fail(p, now_ms, "cannot connect to", e);
    }
}

void drv_port_service(drv_port *p, int64_t now_ms)
{
    if (p->state == DRV_PORT_CONNECTING && now_ms >= p->retry_at_ms)
        fail(p, now_ms, "cannot connect to", ETIMEDOUT);
    if (p->state != DRV_PORT_CLOSED || now_ms < p->retry_at_ms || p->ended)
        return;
    if (p->is_tcp)
        open_tcp(p, now_ms);
    else
        open_serial(p, now_ms);
}

int drv_port_fd(const drv_port *p) { return p->state == DRV_PORT_CLOSED ? -1 : p->fd; }
short drv_port_events(const drv_port *p) { return p->state == DRV_PORT_CONNECTING ? POLLOUT : POLLIN; }

long drv_port_ready(drv_port *p, short revents, uint8_t *buf, size_t cap, int64_t now_ms)
{
    if (p->state == DRV_PORT_CONNECTING) {
        if (!(revents & (POLLOUT | POLLERR | POLLHUP)))
            return 0;
        int err = 0;
        socklen_t len = sizeof err;
        if (getsockopt(p->fd, SOL_SOCKET, SO_ERROR, &err, &len) < 0)
            err = errno;
        if (err) {
            fail(p, now_ms, "cannot connect to", err);
            return -1;
        }
        opened(p);
        return 0;
    }
    if (p->state != DRV_PORT_OPEN || !(revents & (POLLIN | POLLHUP | POLLERR | POLLNVAL)))
        return 0;
    /* read even on POLLHUP: the bytes sent before the hangup still count */
    ssize_t n = read(p->fd, buf, cap);
    if (n > 0) {
        p->bytes_read += n;
        p->backoff_ms = FIRST_BACKOFF_MS; /* the port works: a later loss retries quickly again */
        return (long)n;
    }
    if (n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK || errno == EINTR))
        return 0;
    if (n == 0 && p->is_file) { /* the recording's end: not a loss, nothing to reopen */
        fprintf(stderr, "%s: %s read to its end\n", p->log_prefix, p->path);
        drv_port_close(p);
        p->ended = 1;
        return -1;
    }
    /* 0 after poll said readable is the end of the stream (a TCP peer that
     * closed, a tty that hung up); EIO and ENXIO a device that is gone */
    fail(p, now_ms, n == 0 ? "lost" : "lost (read):", n == 0 ? 0 : errno);
    return -1;
}

int drv_port_write(drv_port *p, const uint8_t *data, size_t n, int64_t now_ms)
{
    if (p->state != DRV_PORT_OPEN)
        return -1;
    if (p->is_file)
        return 0; /* a recording takes no commands: they go nowhere, and count nowhere */
    size_t done = 0;
    while (done < n) {
        ssize_t w = write(p->fd, data + done, n - done);
        if (w > 0) {
            done += (size_t)w;
            continue;
        }
        if (w < 0 && errno == EINTR)
            continue;
        if (w < 0 && (errno == EAGAIN || errno == EWOULDBLOCK))
            break; /* the device's buffer is full: the rest is not written, never waited for */
        fail(p, now_ms, "lost (write):", errno);
        break;
    }
    p->bytes_written += (int64_t)done;
    return done == n ? 0 : -1;
}

int drv_port_ended(const drv_port *p) { return p->ended; }

void drv_port_close(drv_port *p)
{
    if (p->fd >= 0)
        close(p->fd);
    p->fd = -1;
    p->state = DRV_PORT_CLOSED;
}
