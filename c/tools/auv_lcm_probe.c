/* auv-lcm-probe: the C side of the project's LCM checks, and a small tool.
 *
 *   auv-lcm-probe roundtrip DIR
 *       For every type in the generated table, decode the messages in
 *       DIR/<type>.bin (each prefixed by a 4-byte big-endian length), encode
 *       them again and require identical bytes; then require that every
 *       truncation and a corrupted fingerprint are refused, not misread.
 *   auv-lcm-probe publish-track --lcm-url URL --vehicle V --count N --rate HZ
 *       Publish a synthetic vehicle (a 50 m circle at 1.5 m/s) on V.NAV,
 *       V.DEPTH and V.ACTUATORS, built here in C.
 *   auv-lcm-probe listen --lcm-url URL --channel REGEX --type TYPE [--count N] [--timeout-ms MS]
 *       Print each message that decodes as one `field=value` line, then the
 *       receive counters; bad messages are counted and dropped.
 *   auv-lcm-probe field TYPE PATH MSGFILE
 *       Resolve a field path (as managers bind variables) and print its value
 *       in the encoded message MSGFILE.
 *   auv-lcm-probe sha256 FILE
 *       The digest plugin uploads are checked against.
 */
#include <errno.h>
#include <inttypes.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "auv/auv_actuators_t.h"
#include "auv/auv_depth_t.h"
#include "auv/auv_nav_solution_t.h"
#include "common/auv_types.h"
#include "common/field_path.h"
#include "common/lcm_rx.h"
#include "common/msg_print.h"
#include "common/auth_mac.h"
#include "common/time_policy.h"

static const char *opt(int argc, char **argv, const char *name, const char *fallback)
{
    for (int i = 0; i + 1 < argc; i++)
        if (!strcmp(argv[i], name))
            return argv[i + 1];
    return fallback;
}

/* ------------------------------------------------------------ roundtrip */

static unsigned char *read_file(const char *path, size_t *len)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return NULL;
    fseek(f, 0, SEEK_END);
    long n = ftell(f);
    fseek(f, 0, SEEK_SET);
    unsigned char *buf = malloc(n > 0 ? (size_t)n : 1);
    if (buf && fread(buf, 1, (size_t)n, f) != (size_t)n) {
        free(buf);
        buf = NULL;
    }
    fclose(f);
    *len = (size_t)n;
    return buf;
}

/* Returns the number of failures for one encoded message. */
static int check_one(const auv_type_entry_t *t, const unsigned char *msg, int len)
{
    const lcm_type_info_t *info = t->info();
    void *decoded = calloc(1, t->struct_size);
    int failures = 0;
    if (rx_decode(t, msg, len, decoded) != 0) {
        fprintf(stderr, "%s: decode failed\n", t->lcm_name);
        free(decoded);
        return 1;
    }
    int size = info->encoded_size(decoded);
    unsigned char *again = malloc((size_t)size);
    int wrote = info->encode(again, 0, size, decoded);
    if (size != len || wrote != len || memcmp(again, msg, (size_t)len) != 0) {
        fprintf(stderr, "%s: re-encoding differs (%d bytes in, %d out)\n", t->lcm_name, len, wrote);
        failures++;
    }
    info->decode_cleanup(decoded);
    /* Every strict prefix must be refused: a short read is never a message. */
    for (int cut = 0; cut < len; cut++) {
        unsigned char *prefix = malloc((size_t)(cut ? cut : 1));
        memcpy(prefix, msg, (size_t)cut);
        if (rx_decode(t, prefix, cut, decoded) == 0) {
            fprintf(stderr, "%s: %d-byte prefix of %d decoded as a message\n", t->lcm_name, cut, len);
            info->decode_cleanup(decoded);
            failures++;
        }
        free(prefix);
    }
    memcpy(again, msg, (size_t)len);
    again[3] ^= 0x5a;
    if (rx_decode(t, again, len, decoded) != -1) {
        fprintf(stderr, "%s: corrupted fingerprint not refused\n", t->lcm_name);
        failures++;
    }
    free(again);
    free(decoded);
    return failures;
}

static int cmd_roundtrip(const char *dir)
{
    int failures = 0;
    for (size_t i = 0; i < auv_type_table_len; i++) {
        const auv_type_entry_t *t = &auv_type_table[i];
        char path[4096];
        snprintf(path, sizeof path, "%s/%s.bin", dir, t->lcm_name);
        size_t len;
        unsigned char *buf = read_file(path, &len);
        if (!buf) {
            fprintf(stderr, "%s: no samples (%s: %s)\n", t->lcm_name, path, strerror(errno));
            failures++;
            continue;
        }
        int count = 0, bad = 0;
        for (size_t off = 0; off + 4 <= len;) {
            uint32_t n = (uint32_t)buf[off] << 24 | (uint32_t)buf[off + 1] << 16 |
                         (uint32_t)buf[off + 2] << 8 | buf[off + 3];
            off += 4;
            if (n > len - off) {
                fprintf(stderr, "%s: sample file is cut short\n", t->lcm_name);
                bad++;
                break;
            }
            bad += check_one(t, buf + off, (int)n);
            off += n;
            count++;
        }
        printf("%s %s %d\n", bad || !count ? "FAIL" : "ok", t->lcm_name, count);
        failures += bad + !count;
        free(buf);
    }
    return failures ? 1 : 0;
}

/* ------------------------------------------------------------ publish-track */

static void sleep_us(int64_t us)
{
    struct timespec ts = {us / 1000000, (long)(us % 1000000) * 1000};
    while (nanosleep(&ts, &ts) == -1 && errno == EINTR) {
    }
}

static int cmd_publish_track(lcm_t *lcm, const char *vehicle, int count, double rate_hz)
{
    char nav_ch[64], depth_ch[64], act_ch[64];
    snprintf(nav_ch, sizeof nav_ch, "%s.NAV", vehicle);
    snprintf(depth_ch, sizeof depth_ch, "%s.DEPTH", vehicle);
    snprintf(act_ch, sizeof act_ch, "%s.ACTUATORS", vehicle);
    const double radius = 50.0, speed = 1.5, omega = speed / radius;
    for (int i = 0; i < count; i++) {
        double t = i / rate_hz;
        int64_t utime = (int64_t)llround(t * 1e6);
        char *veh = (char *)vehicle;

        auv_nav_solution_t nav;
        memset(&nav, 0, sizeof nav);
        nav.utime = utime;
        nav.vehicle = veh;
        nav.source = AUV_NAV_SOLUTION_T_SOURCE_TRUTH;
        nav.status = AUV_NAV_SOLUTION_T_STATUS_ALIGNED;
        nav.north_m = radius * sin(omega * t);
        nav.east_m = radius * (1.0 - cos(omega * t));
        nav.depth_m = 5.0 + 0.5 * sin(0.1 * t);
        nav.altitude_m = 20.0 - nav.depth_m;
        nav.heading_rad = fmod(omega * t, 2 * M_PI);
        nav.u_mps = speed;
        nav.r_radps = omega;
        nav.speed_over_ground_mps = speed;
        for (int k = 0; k < 3; k++)
            nav.position_cov_m2[k][k] = 0.25 + 0.001 * i;
        auv_nav_solution_t_publish(lcm, nav_ch, &nav);

        auv_depth_t depth = {.utime = utime, .vehicle = veh, .depth_m = nav.depth_m,
                             .pressure_pa = 101325.0 + 1025.0 * 9.81 * nav.depth_m,
                             .temperature_c = 12.0, .valid = 1};
        auv_depth_t_publish(lcm, depth_ch, &depth);

        auv_actuators_t act = {.utime = utime, .vehicle = veh, .rudder_rad = -0.05,
                               .stern_plane_rad = 0.0, .prop_rpm = 1500.0, .seq = i};
        auv_actuators_t_publish(lcm, act_ch, &act);
        if (i + 1 < count)
            sleep_us((int64_t)(1e6 / rate_hz));
    }
    return 0;
}

/* ------------------------------------------------------------ listen */

typedef struct {
    const auv_type_entry_t *type;
    int delivered;
} listen_ctx_t;

static void on_listen(const char *channel, const void *msg, int64_t recv_utime, void *user)
{
    (void)recv_utime;
    listen_ctx_t *ctx = user;
    printf("%s ", channel);
    msg_print(stdout, ctx->type, msg);
    fflush(stdout);
    ctx->delivered++;
}

static int64_t mono_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (int64_t)ts.tv_sec * 1000 + ts.tv_nsec / 1000000;
}

static int cmd_listen(lcm_t *lcm, const char *channel, const char *type_name, int count, int timeout_ms)
{
    const auv_type_entry_t *type = auv_type_find(type_name);
    if (!type) {
        fprintf(stderr, "auv-lcm-probe: unknown type '%s'\n", type_name);
        return 2;
    }
    listen_ctx_t ctx = {type, 0};
    rx_sub_t *sub = rx_subscribe(lcm, channel, type, on_listen, &ctx);
    if (!sub) {
        fprintf(stderr, "auv-lcm-probe: cannot subscribe to '%s'\n", channel);
        return 2;
    }
    /* a pattern matches channels of other types: those are skipped, counted
     * in the stats line, not an error per message */
    rx_set_quiet_other_types(sub, 1);
    printf("ready\n");
    fflush(stdout);
    int64_t deadline = mono_ms() + timeout_ms;
    while ((count <= 0 || ctx.delivered < count) && mono_ms() < deadline)
        lcm_handle_timeout(lcm, 50);
    const rx_stats_t *s = rx_stats(sub);
    printf("stats received=%" PRIu64 " delivered=%" PRIu64 " wrong_fingerprint=%" PRIu64
           " malformed=%" PRIu64 "\n", s->received, s->delivered, s->wrong_fingerprint, s->malformed);
    rx_unsubscribe(lcm, sub);
    return 0;
}

/* ------------------------------------------------------------ field, sha256 */

static int cmd_field(const char *type_name, const char *path, const char *msg_file)
{
    const auv_type_entry_t *type = auv_type_find(type_name);
    if (!type) {
        fprintf(stderr, "auv-lcm-probe: unknown type '%s'\n", type_name);
        return 2;
    }
    field_ref_t ref;
    char err[256];
    if (field_path_resolve(type, path, &ref, err, sizeof err) != 0) {
        fprintf(stderr, "%s\n", err);
        return 1;
    }
    size_t len;
    unsigned char *buf = read_file(msg_file, &len);
    void *msg = calloc(1, type->struct_size);
    int rc = 1;
    if (buf && msg && rx_decode(type, buf, (int)len, msg) == 0) {
        if (field_ref_is_numeric(&ref))
            printf("%.17g\n", field_ref_get_double(&ref, msg));
        else
            printf("%s\n", field_ref_get_string(&ref, msg));
        type->info()->decode_cleanup(msg);
        rc = 0;
    } else {
        fprintf(stderr, "auv-lcm-probe: %s does not hold a %s\n", msg_file, type->lcm_name);
    }
    free(msg);
    free(buf);
    return rc;
}

static int cmd_sha256(const char *path)
{
    size_t len;
    unsigned char *buf = read_file(path, &len);
    if (!buf) {
        fprintf(stderr, "auv-lcm-probe: %s: %s\n", path, strerror(errno));
        return 2;
    }
    char hex[65];
    auth_sha256_hex(buf, len, hex);
    printf("%s\n", hex);
    free(buf);
    return 0;
}

/* The time rule (common/time_policy.h) on a script, for tests in both builds:
 *   clock V...            offer clock values; prints "ok NOW" or the reason per value
 *   input NOW TOL S...    offer data stamps to one input against clock NOW
 * Values are int64 decimal (INT64_MIN and INT64_MAX allowed). */
static int cmd_time(int argc, char **argv)
{
    if (argc >= 3 && !strcmp(argv[2], "clock")) {
        tp_clock c;
        tp_clock_init(&c, TP_MAX_CLOCK_JUMP_US);
        for (int i = 3; i < argc; i++) {
            tp_reason r = tp_clock_offer(&c, strtoll(argv[i], NULL, 10));
            if (r == TP_OK)
                printf("ok %lld\n", (long long)c.now);
            else
                printf("%s\n", tp_reason_name(r));
        }
        return 0;
    }
    if (argc >= 5 && !strcmp(argv[2], "input")) {
        tp_input in = {0};
        int64_t now = strtoll(argv[3], NULL, 10), tol = strtoll(argv[4], NULL, 10);
        for (int i = 5; i < argc; i++) {
            tp_reason r = tp_input_offer(&in, strtoll(argv[i], NULL, 10), 1, now, tol);
            printf("%s\n", r == TP_OK ? "ok" : tp_reason_name(r));
        }
        return 0;
    }
    fprintf(stderr, "usage: auv-lcm-probe time clock V... | time input NOW TOL STAMP...\n");
    return 2;
}

int main(int argc, char **argv)
{
    if (argc >= 2 && !strcmp(argv[1], "time"))
        return cmd_time(argc, argv);
    if (argc < 2 || !strcmp(argv[1], "--help") || !strcmp(argv[1], "-h")) {
        fprintf(argc < 2 ? stderr : stdout,
                "usage: auv-lcm-probe roundtrip DIR | field TYPE PATH FILE | sha256 FILE | time ...\n"
                "       auv-lcm-probe publish-track|listen [--lcm-url URL] [--vehicle ID] [--count N] [--rate HZ]\n"
                "                     [--channel RE] [--type T] [--timeout-ms MS]\n"
                "  --lcm-url URL   LCM URL (default: $LCM_DEFAULT_URL, else liblcm's default); --url is the old spelling\n");
        return argc < 2 ? 2 : 0;
    }
    if (!strcmp(argv[1], "roundtrip") && argc == 3)
        return cmd_roundtrip(argv[2]);
    if (!strcmp(argv[1], "field") && argc == 5)
        return cmd_field(argv[2], argv[3], argv[4]);
    if (!strcmp(argv[1], "sha256") && argc == 3)
        return cmd_sha256(argv[2]);
    /* --lcm-url (or its old spelling --url); none: liblcm honours $LCM_DEFAULT_URL */
    const char *url = opt(argc, argv, "--lcm-url", opt(argc, argv, "--url", NULL));
    lcm_t *lcm = lcm_create(url);
    if (!lcm) {
        fprintf(stderr, "auv-lcm-probe: cannot open LCM at %s (no multicast route? see README)\n", url ? url : "the default URL");
        return 2;
    }
    int rc = 2;
    if (!strcmp(argv[1], "publish-track"))
        rc = cmd_publish_track(lcm, opt(argc, argv, "--vehicle", "AUV1"),
                               atoi(opt(argc, argv, "--count", "10")),
                               atof(opt(argc, argv, "--rate", "10")));
    else if (!strcmp(argv[1], "listen"))
        rc = cmd_listen(lcm, opt(argc, argv, "--channel", ".*"), opt(argc, argv, "--type", ""),
                        atoi(opt(argc, argv, "--count", "0")),
                        atoi(opt(argc, argv, "--timeout-ms", "5000")));
    else
        fprintf(stderr, "auv-lcm-probe: unknown command '%s'\n", argv[1]);
    lcm_destroy(lcm);
    return rc;
}
