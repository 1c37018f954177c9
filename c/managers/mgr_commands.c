/* Mission commands (start, pause, resume, abort, load plan, stop) and plugin
 * uploads, each answered on <VEHICLE>.MISSION_ACK. An upload is written and
 * hot-loaded only if its SHA-256 matches both its own digest field and an
 * entry of the allowlist: plugins are untrusted input. */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "auv/auv_mission_ack_t.h"
#include "auv/auv_mission_command_t.h"
#include "auv/auv_plugin_upload_t.h"
#include "common/sha256.h"
#include "managers/manager.h"
#include "managers/mgr_upload.h"

static void ack(manager_t *mg, int32_t seq, int8_t result, const char *message)
{
    char channel[80];
    snprintf(channel, sizeof channel, "%s.MISSION_ACK", mg->opt.vehicle);
    auv_mission_ack_t a = {.utime = mg->now_us, .vehicle = (char *)mg->opt.vehicle,
                           .manager = (char *)mg->opt.name, .seq = seq, .result = result,
                           .message = (char *)message};
    auv_mission_ack_t_publish(mg->lcm, channel, &a);
    fprintf(stderr, "%s: ack %d: %s\n", mg->opt.name, seq, message);
}

static int for_me(const manager_t *mg, const char *manager)
{
    return !manager || !*manager || !strcmp(manager, mg->opt.name);
}

static void load_plan(manager_t *mg, const auv_mission_command_t *c)
{
    mgr_bindings nb;
    chasm_machine *nm = manager_load(mg, c->plan_name, c->plan_text, &nb);
    if (!nm) {
        ack(mg, c->seq, AUV_MISSION_ACK_T_RESULT_REJECTED, "plan rejected: see the manager's errors");
        return;
    }
    /* Only now that the new plan is complete does the old one go. The
     * bindings subscribe once in their final place: handlers keep a pointer. */
    mgr_bindings_free(&mg->b, mg->lcm);
    chasm_free(mg->m);
    mg->m = nm;
    mg->b = nb;
    mg->started = 0;
    if (mgr_bindings_subscribe(&mg->b, mg->lcm) != 0) {
        ack(mg, c->seq, AUV_MISSION_ACK_T_RESULT_FAILED, "new plan loaded but its inputs cannot be subscribed");
        return;
    }
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
    switch (c->command) {
    case AUV_MISSION_COMMAND_T_CMD_START:
        mg->opt.wait_start = 0;
        ack(mg, c->seq, AUV_MISSION_ACK_T_RESULT_OK, mg->started ? "already running" : "starting");
        break;
    case AUV_MISSION_COMMAND_T_CMD_PAUSE:
    case AUV_MISSION_COMMAND_T_CMD_RESUME:
        chasm_pause(mg->m, c->command == AUV_MISSION_COMMAND_T_CMD_PAUSE);
        ack(mg, c->seq, AUV_MISSION_ACK_T_RESULT_OK, c->command == AUV_MISSION_COMMAND_T_CMD_PAUSE ? "paused" : "resumed");
        break;
    case AUV_MISSION_COMMAND_T_CMD_ABORT:
        chasm_abort(mg->m, mg->now_us, c->reason && *c->reason ? c->reason : "operator abort");
        ack(mg, c->seq, AUV_MISSION_ACK_T_RESULT_OK, "aborting");
        break;
    case AUV_MISSION_COMMAND_T_CMD_LOAD_PLAN:
        load_plan(mg, c);
        break;
    case AUV_MISSION_COMMAND_T_CMD_STOP:
        mg->stop = 1;
        ack(mg, c->seq, AUV_MISSION_ACK_T_RESULT_OK, "stopping");
        break;
    default:
        ack(mg, c->seq, AUV_MISSION_ACK_T_RESULT_REJECTED, "unknown command");
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
    char text[2048];
    int8_t result = mgr_upload_plugin(mg, u, text, sizeof text);
    ack(mg, u->seq, result, text);
}

int mgr_commands_subscribe(manager_t *mg)
{
    char ch[80];
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
