/* Test plugin for message variables: a reader that records what it takes, a
 * relay, and a poster of good, oversized and NULL messages. Its check proves
 * the load-time api hands out no messages and takes no posts. */
#include <stdio.h>
#include <string.h>

#include "chasm/chasm_plugin.h"

/* take: every message (or at most `max` per call) as text, joined by ','
 * into `log` (the last 1000 characters), their number into `count`. */
static const chasm_param_spec take_params[] = {
    CHASM_READ_REQUIRED("rx", CHASM_MESSAGES, "", "messages to take"),
    CHASM_WRITE_REQUIRED("log", CHASM_STRING, "", "what was taken, in order"),
    CHASM_WRITE_REQUIRED("count", CHASM_INT, "", "how many were taken"),
    CHASM_PARAM_INT_RANGE("max", 0, 0, 1000, "at most this many per call (0: all)"),
    CHASM_WRITE("age", CHASM_DOUBLE, "s", NULL, "age of rx as the plugin sees it"),
};
typedef struct {
    char log[1024];
    int64_t count;
} take_state;

static chasm_status_code take_step(chasm_ctx *c, void *st)
{
    take_state *t = st;
    int64_t max = chasm_param_int(c, 3), n = 0;
    size_t len;
    const void *p;
    while ((max == 0 || n < max) && (p = chasm_next_message(c, 0, &len)) != NULL) {
        n++;
        t->count++;
        size_t have = strlen(t->log);
        if (have + len + 2 >= sizeof t->log) {  /* keep the tail: drop the oldest half */
            memmove(t->log, t->log + have / 2, have - have / 2 + 1);
            have = strlen(t->log);
        }
        if (have + len + 2 < sizeof t->log) {
            if (have) t->log[have++] = ',';
            memcpy(t->log + have, p, len);
            t->log[have + len] = 0;
        }
    }
    chasm_write_string(c, 1, t->log);
    chasm_write_int(c, 2, t->count);
    chasm_write_double(c, 4, chasm_age_s(c, 0));
    return CHASM_RUNNING;
}

/* relay: posts every message it takes from rx to tx, unchanged. */
static const chasm_param_spec relay_params[] = {
    CHASM_READ_REQUIRED("rx", CHASM_MESSAGES, "", "messages to take"),
    CHASM_WRITE_REQUIRED("tx", CHASM_MESSAGES, "", "where they go"),
};
static chasm_status_code relay_step(chasm_ctx *c, void *st)
{
    (void)st;
    size_t len;
    const void *p;
    while ((p = chasm_next_message(c, 0, &len)) != NULL) chasm_post_message(c, 1, p, len);
    return CHASM_RUNNING;
}

/* post: each call posts `n` messages "<text><k>" (k counts up over calls), or
 * one of `size` bytes of 'x' when size > 0, or NULL bytes when `null`;
 * `refused` counts the refusals it got back. */
static const chasm_param_spec post_params[] = {
    CHASM_WRITE_REQUIRED("tx", CHASM_MESSAGES, "", "where to post"),
    CHASM_PARAM_STRING("text", "m", "prefix of each message"),
    CHASM_PARAM_INT_RANGE("n", 1, 0, 10000, "messages per call"),
    CHASM_PARAM_INT_RANGE("size", 0, 0, 1e6, "post one message of this many bytes instead"),
    CHASM_PARAM_BOOL("null", 0, "post NULL with a length of 5"),
    CHASM_WRITE("refused", CHASM_INT, "", NULL, "posts refused so far"),
};
typedef struct {
    int64_t k, refused;
} post_state;
static char big[1000001];
static chasm_status_code post_step(chasm_ctx *c, void *st)
{
    post_state *s = st;
    int64_t size = chasm_param_int(c, 3);
    if (chasm_param_bool(c, 4)) {
        s->refused += chasm_post_message(c, 0, NULL, 5) != 0;
    } else if (size > 0) {
        memset(big, 'x', (size_t)size);
        s->refused += chasm_post_message(c, 0, big, (size_t)size) != 0;
    } else {
        for (int64_t i = 0; i < chasm_param_int(c, 2); i++) {
            char m[64];
            int len = snprintf(m, sizeof m, "%s%lld", chasm_param_string(c, 1), (long long)++s->k);
            s->refused += chasm_post_message(c, 0, m, (size_t)len) != 0;
        }
    }
    chasm_write_int(c, 5, s->refused);
    return CHASM_RUNNING;
}

static const chasm_behavior_spec behaviors[] = {
    {.name = "take", .doc = "records every message it takes", CHASM_SCHEMA(take_params),
     .state_size = sizeof(take_state), .step = take_step},
    {.name = "relay", .doc = "posts what it takes", CHASM_SCHEMA(relay_params), .step = relay_step},
    {.name = "post", .doc = "posts messages", CHASM_SCHEMA(post_params), .state_size = sizeof(post_state),
     .step = post_step},
};

CHASM_PLUGIN_EXPORT("test_msgs", "1.0.0", CHASM_BEHAVIORS(behaviors));

/* At load nothing can be taken or posted: a check that could would be
 * consuming the mission's messages before it starts. */
CHASM_PLUGIN_CHECK(check)
static int check(const char *item, const chasm_ctx *c, int *slot, char *why, size_t whylen)
{
    chasm_ctx *cc = (chasm_ctx *)c;
    size_t len = 99;
    int rx = !strcmp(item, "post") ? -1 : 0, tx = !strcmp(item, "take") ? -1 : !strcmp(item, "post") ? 0 : 1;
    if (rx >= 0 && (chasm_next_message(cc, rx, &len) != NULL || len != 0)) {
        *slot = rx;
        snprintf(why, whylen, "the check was handed a message");
        return 1;
    }
    if (tx >= 0 && chasm_post_message(cc, tx, "x", 1) == 0) {
        *slot = tx;
        snprintf(why, whylen, "the check could post");
        return 1;
    }
    return 0;
}
