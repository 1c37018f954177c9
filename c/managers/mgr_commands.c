/* Mission commands (start, pause, resume, abort, load plan, stop) and plugin
 * uploads, each answered on <VEHICLE>.MISSION_ACK. An upload is written and
 * hot-loaded only if its SHA-256 matches both its own digest field and an
 * entry of the allowlist: plugins are untrusted input. */
#include <errno.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "auv/auv_mission_ack_t.h"
#include "auv/auv_mission_command_t.h"
#include "auv/auv_plugin_upload_t.h"
#include "managers/mgr_auth.h"
#include "managers/mgr_commands.h"
#include "managers/mgr_upload.h"

static void publish_ack(manager_t *mg, int32_t seq, int8_t result, const char *message)
{
    char channel[MGR_MAX_CHANNEL + 1];
    snprintf(channel, sizeof channel, "%s.MISSION_ACK", mg->opt.vehicle);
    auv_mission_ack_t a = {.utime = mg->now_us, .vehicle = (char *)mg->opt.vehicle,
                           .manager = (char *)mg->opt.name, .seq = seq, .result = result,
                           .message = (char *)message};
    auv_mission_ack_t_publish(mg->lcm, channel, &a);
}

static void ack(manager_t *mg, int32_t seq, int8_t result, const char *message)
{
    publish_ack(mg, seq, result, message);
    fprintf(stderr, "%s: ack %d: %s\n", mg->opt.name, seq, message);
}

static int for_me(const manager_t *mg, const char *manager)
{
    return !manager || !*manager || !strcmp(manager, mg->opt.name);
}

static void refuse(manager_t *mg, int32_t seq, const char *fmt, ...) __attribute__((format(printf, 3, 4)));
static void refuse(manager_t *mg, int32_t seq, const char *fmt, ...)
{
    char text[MGR_ACK_MAX_CHARS + 1];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(text, sizeof text, fmt, ap);
    va_end(ap);
    mg->commands_refused++;
    ack(mg, seq, AUV_MISSION_ACK_T_RESULT_REJECTED, text);
}

/* Printable ASCII only, at most max characters (NULL counts as ""). */
static int plain_text(const char *s, size_t max)
{
    size_t n = 0;
    for (; s && s[n]; n++)
        if ((unsigned char)s[n] < 0x20 || (unsigned char)s[n] >= 0x7f)
            return 0;
    return n <= max;
}

/* A field for the ack: its first characters, never control bytes. */
static const char *shown(const char *s, char *buf, size_t cap)
{
    size_t o = 0;
    for (size_t i = 0; s && s[i] && o + 4 < cap && i < MGR_ACK_FIELD_CHARS; i++)
        buf[o++] = (unsigned char)s[i] < 0x20 || (unsigned char)s[i] >= 0x7f ? '?' : s[i];
    if (s && strlen(s) > MGR_ACK_FIELD_CHARS && o + 4 < cap) {
        memcpy(buf + o, "...", 3);
        o += 3;
    }
    buf[o] = '\0';
    return buf;
}

/* The fields every command and upload share: a message for another vehicle
 * or with a bad stamp is refused (and acknowledged as such), never executed.
 * Returns 1 when the message may proceed. */
static int header_ok(manager_t *mg, int64_t utime, const char *vehicle, int32_t seq)
{
    char b[64];
    if (!vehicle || strcmp(vehicle, mg->opt.vehicle)) {
        refuse(mg, seq, "refused: addressed to vehicle '%s', this is %s", shown(vehicle, b, sizeof b), mg->opt.vehicle);
        return 0;
    }
    if (!tp_utime_valid(utime)) {
        refuse(mg, seq, "refused: utime %lld is outside 0..%lld us", (long long)utime, (long long)TP_UTIME_MAX);
        return 0;
    }
    return 1;
}

/* Authentication comes first: nothing of an unauthenticated message is
 * acted on or echoed but its seq. Returns 1 when the message may proceed. */
static int authentic(manager_t *mg, auth_result r, int32_t seq)
{
    if (r == AUTH_OK)
        return 1;
    char text[160];
    snprintf(text, sizeof text, "refused: %s", auth_result_text(r));
    mg->commands_refused++;
    publish_ack(mg, seq, AUV_MISSION_ACK_T_RESULT_REJECTED, text);
    /* Logged as they come only at first: a flood must not fill the log (or
     * block on it); the status counts every one. */
    uint64_t n = ++mg->auth_refusals_logged;
    if (n <= 10 || n % 1000 == 0)
        fprintf(stderr, "%s: ack %d: %s (%llu unauthenticated command(s) refused so far%s)\n", mg->opt.name, seq,
                text, (unsigned long long)n, n == 10 ? "; from now on one line per 1000" : "");
    return 0;
}

/* Field checks of a mission command; NULL when valid, else the reason. */
static const char *command_fields_bad(const manager_t *mg, const auv_mission_command_t *c, char *why, size_t cap)
{
    int load = c->command == AUV_MISSION_COMMAND_T_CMD_LOAD_PLAN;
    size_t text_len = c->plan_text ? strlen(c->plan_text) : 0;
    if (c->command < AUV_MISSION_COMMAND_T_CMD_START || c->command > AUV_MISSION_COMMAND_T_CMD_STOP)
        snprintf(why, cap, "unknown command %d (0..%d)", c->command, AUV_MISSION_COMMAND_T_CMD_STOP);
    else if (!plain_text(c->reason, MGR_MAX_REASON))
        snprintf(why, cap, "reason must be printable text of at most %d characters", MGR_MAX_REASON);
    else if (!load && ((c->plan_name && *c->plan_name) || text_len))
        snprintf(why, cap, "plan_name and plan_text are only for LOAD_PLAN");
    else if (load && (!c->plan_name || !*c->plan_name || !plain_text(c->plan_name, MGR_MAX_PLAN_NAME)))
        snprintf(why, cap, "LOAD_PLAN needs a plan_name of 1 to %d printable characters", MGR_MAX_PLAN_NAME);
    else if (load && text_len == 0)
        snprintf(why, cap, "LOAD_PLAN needs a plan_text");
    else if (load && text_len > mg->max_plan_bytes)
        snprintf(why, cap, "plan is %zu bytes, the maximum is %zu bytes", text_len, mg->max_plan_bytes);
    else
        return NULL;
    return why;
}

static void load_plan(manager_t *mg, const auv_mission_command_t *c)
{
    manager_plan plan;
    mgr_errors errs = {0};
    if (manager_load(mg, c->plan_name, c->plan_text, &plan, &errs) != 0) {
        char text[MGR_ACK_MAX_CHARS + 1];
        mgr_errors_summary(&errs, MGR_ACK_MAX_ERRORS, text, sizeof text);
        mgr_errors_free(&errs);
        refuse(mg, c->seq, "plan rejected, mission unchanged: %s", text);
        return;
    }
    mgr_errors_free(&errs);
    /* Only now that the new plan is complete does the old one go. */
    if (manager_replace_plan(mg, &plan) != 0) {
        ack(mg, c->seq, AUV_MISSION_ACK_T_RESULT_FAILED, "new plan loaded but its inputs cannot be subscribed");
        return;
    }
    mgr_status_set_plan(&mg->status, c->plan_name);
    ack(mg, c->seq, AUV_MISSION_ACK_T_RESULT_OK, "plan loaded");
}

static void on_command(const char *channel, const void *msg, int64_t recv_utime, void *user)
{
    (void)channel;
    (void)recv_utime;
    manager_t *mg = user;
    const auv_mission_command_t *c = msg;
    if (!for_me(mg, c->manager))
        return;
    if (!authentic(mg, mgr_auth_command(&mg->auth, c), c->seq))
        return;
    if (!header_ok(mg, c->utime, c->vehicle, c->seq))
        return;
    char why[200];
    if (command_fields_bad(mg, c, why, sizeof why)) {
        refuse(mg, c->seq, "refused: %s", why);
        return;
    }
    switch (c->command) {
    case AUV_MISSION_COMMAND_T_CMD_START:
        ack(mg, c->seq, AUV_MISSION_ACK_T_RESULT_OK, manager_request_start(mg) ? "already running" : "starting");
        break;
    case AUV_MISSION_COMMAND_T_CMD_PAUSE:
    case AUV_MISSION_COMMAND_T_CMD_RESUME:
        chasm_pause(mg->plan.machine, c->command == AUV_MISSION_COMMAND_T_CMD_PAUSE);
        ack(mg, c->seq, AUV_MISSION_ACK_T_RESULT_OK, c->command == AUV_MISSION_COMMAND_T_CMD_PAUSE ? "paused" : "resumed");
        break;
    case AUV_MISSION_COMMAND_T_CMD_ABORT:
        chasm_abort(mg->plan.machine, mg->now_us, c->reason && *c->reason ? c->reason : "operator abort");
        ack(mg, c->seq, AUV_MISSION_ACK_T_RESULT_OK, "aborting");
        break;
    case AUV_MISSION_COMMAND_T_CMD_LOAD_PLAN:
        load_plan(mg, c);
        break;
    case AUV_MISSION_COMMAND_T_CMD_STOP:
        manager_request_stop(mg);
        ack(mg, c->seq, AUV_MISSION_ACK_T_RESULT_OK, "stopping");
        break;
    default: /* command_fields_bad() refused it already */
        break;
    }
}

static void on_upload(const char *channel, const void *msg, int64_t recv_utime, void *user)
{
    (void)channel;
    (void)recv_utime;
    manager_t *mg = user;
    const auv_plugin_upload_t *u = msg;
    if (!for_me(mg, u->manager))
        return;
    if (!authentic(mg, mgr_auth_upload(&mg->auth, u), u->seq))
        return;
    if (!header_ok(mg, u->utime, u->vehicle, u->seq))
        return;
    char text[MGR_ACK_MAX_CHARS + 1];
    int8_t result = mgr_upload_plugin(mg, u, text, sizeof text);
    ack(mg, u->seq, result, text);
}

int mgr_commands_subscribe(manager_t *mg)
{
    char ch[MGR_MAX_CHANNEL + 1];
    snprintf(ch, sizeof ch, "%s.MISSION_CMD", mg->opt.vehicle);
    if (!(mg->cmd_sub = rx_subscribe(mg->lcm, ch, auv_type_find("mission_command_t"), on_command, mg)))
        return -1;
    snprintf(ch, sizeof ch, "%s.PLUGIN_UPLOAD", mg->opt.vehicle);
    if (!(mg->upload_sub = rx_subscribe(mg->lcm, ch, auv_type_find("plugin_upload_t"), on_upload, mg)))
        return -1;
    mgr_upload_clean_dir(mg);
    return 0;
}

void mgr_commands_unsubscribe(manager_t *mg)
{
    rx_unsubscribe(mg->lcm, mg->cmd_sub);
    rx_unsubscribe(mg->lcm, mg->upload_sub);
    mg->cmd_sub = mg->upload_sub = NULL;
}

uint64_t mgr_commands_decode_errors(const manager_t *mg)
{
    return (mg->cmd_sub ? rx_decode_errors(mg->cmd_sub) : 0) +
           (mg->upload_sub ? rx_decode_errors(mg->upload_sub) : 0);
}
