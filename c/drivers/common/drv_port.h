/* A driver's port: a serial line (termios raw mode, 8N1, no flow control, at
 * a given baud) or a TCP client (a serial-to-Ethernet server, a device on the
 * network). Non-blocking throughout, TCP connect included: the loop never
 * waits on the port. A port that vanishes (EOF, EIO, ENXIO, POLLHUP, a
 * refused or reset connection) is closed and opened again after a backoff
 * that doubles from 100 ms to DRV_PORT_MAX_BACKOFF_MS; each reopening after a
 * loss counts in `reopens`.
 *
 * `--device` may also name what is not a serial line: a FIFO is read as a
 * line without settings (held open for writing too, so a writer that goes
 * and comes back is no end), and a regular file is a recording: read once,
 * to its end, never written to (a protocol's commands are not sent), after
 * which the port has ended (drv_port_ended) and the driver stops. */
#ifndef DRV_PORT_H
#define DRV_PORT_H

#include <stddef.h>
#include <stdint.h>

#define DRV_PORT_MAX_BACKOFF_MS 2000

typedef enum { DRV_PORT_CLOSED, DRV_PORT_CONNECTING, DRV_PORT_OPEN } drv_port_state;

typedef struct {
    int is_tcp;
    int is_file;           /* a regular file: a recording, read once */
    int ended;             /* the recording's end was read: never opened again */
    char path[256];        /* serial device, FIFO or recording */
    int baud;
    char host[256], service[32];
    char name[300];        /* "/dev/ttyUSB0@9600" or "tcp:10.0.0.2:4001" */

    drv_port_state state;
    int fd;
    int64_t retry_at_ms;   /* monotonic ms of the next attempt while closed */
    int backoff_ms;
    int was_open;          /* opened at least once: the next open is a reopen */
    int64_t reopens;
    int64_t bytes_read, bytes_written;
    char last_error[400];
    char logged_error[400]; /* the last error logged: a retry failing the same way is not logged again */
    const char *log_prefix; /* "auv-gps: GPS" */
} drv_port;

/* Is baud one termios knows (1200 .. 921600)? */
int drv_port_baud_ok(int baud);

/* Configure; no I/O yet. -1 with a message in err for a bad HOST:PORT. */
void drv_port_serial(drv_port *p, const char *path, int baud, const char *log_prefix);
int drv_port_tcp(drv_port *p, const char *host_port, const char *log_prefix, char *err, size_t errlen);

/* Opens the port if it is closed and its retry time has come. */
void drv_port_service(drv_port *p, int64_t now_ms);

/* The fd and poll events to wait for (-1 while closed). */
int drv_port_fd(const drv_port *p);
short drv_port_events(const drv_port *p);

/* After poll: reads what is there into buf. Returns the number of bytes (0:
 * nothing yet), or -1 when the port was lost (it is closed and a reopen
 * scheduled; the caller resets its protocol). */
long drv_port_ready(drv_port *p, short revents, uint8_t *buf, size_t cap, int64_t now_ms);

/* Writes all of data or nothing useful: -1 if the port is not open or the
 * write failed (a lost port is closed). */
int drv_port_write(drv_port *p, const uint8_t *data, size_t n, int64_t now_ms);

void drv_port_close(drv_port *p);

/* A recording read to its end: nothing more will come. */
int drv_port_ended(const drv_port *p);

#endif
