/* Test plugin over real LCM types: decodes each modem_tx_t it takes with the
 * lcm-gen code compiled in (test_msgs_lcm.lcmtypes.list) and posts one
 * modem_tx_t per input (same seq and payload, vehicle "ECHO"). An input with
 * seq -1 makes it post garbage instead (the manager must refuse it), seq -2
 * a message over the size limit (the engine refuses it). */
#include <stdlib.h>
#include <string.h>

#include "auv/auv_modem_tx_t.h"
#include "chasm/chasm_plugin.h"

static const chasm_param_spec echo_params[] = {
    CHASM_READ_REQUIRED("rx", CHASM_MESSAGES, "", "modem_tx_t messages to echo"),
    CHASM_WRITE_REQUIRED("tx", CHASM_MESSAGES, "", "the echoes"),
    CHASM_WRITE_REQUIRED("taken", CHASM_INT, "", "messages taken so far"),
    CHASM_WRITE_REQUIRED("undecodable", CHASM_INT, "", "taken messages that did not decode"),
};
typedef struct {
    int64_t taken, bad;
} echo_state;

static void echo(chasm_ctx *c, const auv_modem_tx_t *in)
{
    if (in->seq == -1) {
        static const char garbage[] = "not an LCM message at all";
        chasm_post_message(c, 1, garbage, sizeof garbage);
        return;
    }
    if (in->seq == -2) {
        static char big[70000];
        chasm_post_message(c, 1, big, sizeof big);
        return;
    }
    auv_modem_tx_t out = *in;
    out.utime = c->now_us;
    out.vehicle = (char *)"ECHO";
    int size = auv_modem_tx_t_encoded_size(&out);
    unsigned char buf[1024];
    if (size <= 0 || size > (int)sizeof buf) return;
    if (auv_modem_tx_t_encode(buf, 0, size, &out) == size) chasm_post_message(c, 1, buf, (size_t)size);
}

static chasm_status_code echo_step(chasm_ctx *c, void *st)
{
    echo_state *s = st;
    size_t len;
    const void *p;
    while ((p = chasm_next_message(c, 0, &len)) != NULL) {
        s->taken++;
        auv_modem_tx_t in;
        if (len > 0x7fffffff || auv_modem_tx_t_decode(p, 0, (int)len, &in) < 0) {
            s->bad++;
            continue;
        }
        echo(c, &in);
        auv_modem_tx_t_decode_cleanup(&in);
    }
    chasm_write_int(c, 2, s->taken);
    chasm_write_int(c, 3, s->bad);
    return CHASM_RUNNING;
}

static const chasm_behavior_spec behaviors[] = {
    {.name = "echo", .doc = "echoes modem_tx_t messages", CHASM_SCHEMA(echo_params), .state_size = sizeof(echo_state),
     .step = echo_step},
};
CHASM_PLUGIN_EXPORT("test_msgs_lcm", "1.0.0", CHASM_BEHAVIORS(behaviors));
