/* Message variables: order, once per reader, two readers, missed counting,
 * capacity, posts, age, hot plug, and the host's append/take. */
#include <stdlib.h>

#include "../../harness/plan_test.h"

static int id(chasm_machine *m, const char *name) { return chasm_var_find(m, name); }

static void add(chasm_machine *m, const char *var, const char *text, double t)
{
    if (chasm_messages_append(m, id(m, var), text, strlen(text), (int64_t)(t * 1e6)))
        UNIT_FAIL("cannot append to %s", var);
}

static const char *str(chasm_machine *m, const char *var) { return chasm_var_get_string(m, id(m, var)); }

static chasm_messages_info info(chasm_machine *m, const char *var)
{
    chasm_messages_info mi = {0};
    CHECK(chasm_messages_stats(m, id(m, var), &mi) == 0);
    return mi;
}

static const char *READ_PLAN =
    "use test_msgs\n"
    "input rx : messages\n"
    "output a.log : string\noutput a.n : int\noutput b.log : string\noutput b.n : int\n"
    "state s {\n do take(rx = rx, log = a.log, count = a.n)\n do take(rx = rx, log = b.log, count = b.n)\n}\n";

/* Each reader sees every message once, in order; two readers both see all. */
static void stream_order_two_readers(void)
{
    chasm_machine *m = pt_load(READ_PLAN);
    if (!m) return;
    CHECK(chasm_var_type(m, id(m, "rx")) == CHASM_MESSAGES);
    CHECK(info(m, "rx").capacity == 64);
    add(m, "rx", "1", 0);
    chasm_start(m, 0);
    add(m, "rx", "2", 0.05);
    add(m, "rx", "3", 0.05);
    pt_run_until(m, 0.1, 0.1);
    CHECK_STR(str(m, "a.log"), "1,2,3");
    CHECK_STR(str(m, "b.log"), "1,2,3");
    pt_run_until(m, 0.2, 0.3); /* nothing new: nothing taken twice */
    CHECK(pt_get_int(m, "a.n") == 3 && pt_get_int(m, "b.n") == 3);
    add(m, "rx", "4", 0.35);
    pt_run_until(m, 0.4, 0.4);
    CHECK_STR(str(m, "a.log"), "1,2,3,4");
    CHECK_STR(str(m, "b.log"), "1,2,3,4");
    chasm_messages_info mi = info(m, "rx");
    CHECK(mi.total == 4 && mi.missed == 0 && mi.refused == 0);
    chasm_free(m);
}

/* A reader more than `capacity` behind loses the oldest, counted; never a repeat. */
static void stream_missed_and_capacity(void)
{
    chasm_machine *m = pt_load("use test_msgs\ninput rx : messages(4)\noutput a.log : string\noutput a.n : int\n"
                                 "state s {\n do take(rx = rx, log = a.log, count = a.n, max = 1)\n}\n");
    if (!m) return;
    CHECK(info(m, "rx").capacity == 4);
    chasm_start(m, 0);
    char t[12]; /* any int: -O1 cannot bound i */
    for (int i = 1; i <= 10; i++) {
        snprintf(t, sizeof t, "%d", i);
        add(m, "rx", t, 0.05);
    }
    pt_run_until(m, 0.1, 0.1);
    CHECK_STR(str(m, "a.log"), "7");     /* 1..6 were overwritten before it looked */
    CHECK(info(m, "rx").missed == 6);
    pt_run_until(m, 0.2, 0.6);
    CHECK_STR(str(m, "a.log"), "7,8,9,10");
    CHECK(pt_get_int(m, "a.n") == 4);
    chasm_messages_info mi = info(m, "rx");
    CHECK(mi.total == 10 && mi.missed == 6);
    chasm_free(m);
}

/* Posts enter the stream when the cycle ends, in order; the host takes them
 * once; more than `capacity` in one cycle, too large or NULL are refused. */
static void stream_posts(void)
{
    chasm_machine *m = pt_load("use test_msgs\noutput tx : messages(3)\noutput r : int\n"
                                 "state s {\n do post(tx = tx, text = \"p\", n = 4, refused = r)\n}\n");
    if (!m) return;
    chasm_start(m, 0);
    int tx = id(m, "tx");
    size_t len;
    const char *got[8] = {0};
    int n = 0;
    const void *p;
    CHECK(chasm_messages_take(m, tx, &len) == NULL); /* entering runs no `do` step: nothing posted yet */
    pt_run_until(m, 0.1, 0.1);
    while (n < 8 && (p = chasm_messages_take(m, tx, &len)) != NULL) got[n++] = strndup(p, len);
    CHECK(n == 3);
    if (n == 3) {
        CHECK_STR(got[0], "p1");
        CHECK_STR(got[2], "p3");
    }
    for (int i = 0; i < n; i++) free((void *)got[i]);
    CHECK(chasm_messages_take(m, tx, &len) == NULL && len == 0);
    CHECK(pt_get_int(m, "r") == 1);   /* the fourth of the cycle */
    CHECK(info(m, "tx").refused == 1 && info(m, "tx").total == 3);
    CHECK(chasm_var_updated_us(m, tx) == 100000);
    pt_run_until(m, 0.2, 0.3);      /* the host did not take: it lost the oldest three */
    CHECK(chasm_messages_take(m, tx, &len) != NULL && len == 2 && !memcmp(chasm_messages_take(m, tx, &len), "p10", 3));
    CHECK(info(m, "tx").missed == 3);
    chasm_free(m);

    m = pt_load("use test_msgs\noutput tx : messages\noutput tx2 : messages\noutput r : int\noutput r2 : int\n"
                  "state s {\n do post(tx = tx, size = 65537, refused = r)\n do post(tx = tx2, null = true, refused = r2)\n}\n");
    if (!m) return;
    chasm_start(m, 0);
    pt_run_until(m, 0.1, 0.2);
    CHECK(pt_get_int(m, "r") == 2 && pt_get_int(m, "r2") == 2);
    CHECK(chasm_messages_take(m, id(m, "tx"), &len) == NULL);
    CHECK(chasm_messages_take(m, id(m, "tx2"), &len) == NULL);
    CHECK(info(m, "tx").refused == 2 && info(m, "tx").total == 0);
    CHECK(strstr(pt_log, "was refused") != NULL);
    chasm_free(m);
}

/* The host side refuses what does not fit, and anything but a messages variable. */
static void stream_host_refusals(void)
{
    chasm_machine *m = pt_load("input rx : messages\ninput d : double\nstate s {\n}\n");
    if (!m) return;
    static char big[CHASM_MESSAGE_MAX_BYTES + 1];
    CHECK(chasm_messages_append(m, id(m, "rx"), big, sizeof big, 0) == -1);
    CHECK(chasm_messages_append(m, id(m, "rx"), big, CHASM_MESSAGE_MAX_BYTES, 0) == 0);
    CHECK(chasm_messages_append(m, id(m, "rx"), NULL, 3, 0) == -1);
    CHECK(chasm_messages_append(m, id(m, "rx"), NULL, 0, 0) == 0); /* an empty message is a message */
    CHECK(chasm_messages_append(m, id(m, "d"), "x", 1, 0) == -1);
    CHECK(chasm_messages_append(m, -1, "x", 1, 0) == -1);
    CHECK(chasm_messages_append(m, 99, "x", 1, 0) == -1);
    CHECK(chasm_var_set_double(m, id(m, "rx"), 1.0, 0) == -1);
    size_t len = 7;
    CHECK(chasm_messages_take(m, id(m, "d"), &len) == NULL && len == 0);
    chasm_messages_info mi;
    CHECK(chasm_messages_stats(m, id(m, "d"), &mi) == -1);
    CHECK(info(m, "rx").total == 2);
    CHECK(chasm_messages_take(m, id(m, "rx"), &len) != NULL && len == CHASM_MESSAGE_MAX_BYTES);
    CHECK(chasm_messages_take(m, id(m, "rx"), &len) != NULL && len == 0);
    CHECK(chasm_messages_take(m, id(m, "rx"), &len) == NULL);
    chasm_free(m);
}

/* `age` of a stream is the time since its newest message; an action entered
 * later does not get messages from before the previous cycle. */
static void stream_age_and_entry(void)
{
    chasm_machine *m = pt_load("use test_msgs\ninput rx : messages\ninput go : bool\n"
                                 "output a.log : string\noutput a.n : int\noutput a.age : double s\n"
                                 "test quiet : age rx > 1.5 s\ntest go_on : go == true\n"
                                 "state wait {\n when go_on -> read\n}\n"
                                 "state read {\n do take(rx = rx, log = a.log, count = a.n, age = a.age)\n when quiet -> finished\n}\n"
                                 "state finished {\n}\n");
    if (!m) return;
    chasm_start(m, 0);
    add(m, "rx", "old", 0.05);
    pt_run_until(m, 0.1, 0.2);
    add(m, "rx", "new", 0.25);
    pt_set_bool(m, "go", 1, 0.25);
    pt_run_until(m, 0.3, 0.4); /* `read` entered at 0.3: "old" came two cycles before */
    CHECK_STR(pt_leaf(m), "read");
    CHECK_STR(str(m, "a.log"), "new");
    CHECK(pt_get(m, "a.age") > 0.14 && pt_get(m, "a.age") < 0.16); /* at 0.4 s, since 0.25 s */
    pt_run_until(m, 0.5, 1.7);
    CHECK_STR(pt_leaf(m), "read");
    add(m, "rx", "again", 1.7);
    pt_run_until(m, 1.8, 3.1);
    CHECK_STR(pt_leaf(m), "read");
    pt_run_until(m, 3.2, 3.3);
    CHECK_STR(pt_leaf(m), "finished"); /* quiet for over 1.5 s since 1.7 s */
    CHECK_STR(str(m, "a.log"), "new,again");
    chasm_free(m);
}

/* A local stream: one action posts, another reads from the next cycle on. */
static void stream_local_relay(void)
{
    chasm_machine *m = pt_load("use test_msgs\ninput rx : messages\nvar mid : messages(8)\n"
                                 "output a.log : string\noutput a.n : int\n"
                                 "state s {\n do relay(rx = rx, tx = mid)\n do take(rx = mid, log = a.log, count = a.n)\n}\n");
    if (!m) return;
    chasm_start(m, 0);
    add(m, "rx", "x", 0.05);
    add(m, "rx", "y", 0.05);
    pt_run_until(m, 0.1, 0.1);
    CHECK(pt_get_int(m, "a.n") == 0);
    pt_run_until(m, 0.2, 0.3);
    CHECK_STR(str(m, "a.log"), "x,y");
    chasm_free(m);
}

/* A hot plug swaps the code, not the streams: nothing lost, nothing repeated. */
static void stream_hotplug_keeps(void)
{
    chasm_machine *m = pt_load("use test_msgs\ninput rx : messages\ninput go : bool\n"
                                 "output a.log : string\noutput a.n : int\n"
                                 "test go_on : go == true\ntest go_off : go == false\n"
                                 "state s {\n do take(rx = rx, log = a.log, count = a.n)\n when go_on -> t\n}\n"
                                 "state t {\n when go_off -> s\n}\n");
    if (!m) return;
    chasm_start(m, 0);
    pt_set_bool(m, "go", 0, 0);
    add(m, "rx", "1", 0.05);
    pt_run_until(m, 0.1, 0.1);
    char p[1024], err[2048];
    snprintf(p, sizeof p, "%s/chasm_test_msgs.so", unit_plugin_dir);
    int rc = chasm_hotplug(m, p, err, sizeof err);
    if (rc) fprintf(stderr, "%s\n", err);
    CHECK(rc == 0);
    add(m, "rx", "2", 0.15);
    pt_run_until(m, 0.2, 0.2);
    CHECK_STR(str(m, "a.log"), "1,2"); /* old code still runs until re-entry */
    pt_set_bool(m, "go", 1, 0.2);
    pt_run_until(m, 0.3, 0.3);
    pt_set_bool(m, "go", 0, 0.3);
    add(m, "rx", "3", 0.35);
    pt_run_until(m, 0.4, 0.5); /* back in s with the new code: a fresh instance sees this cycle's on */
    CHECK_STR(pt_leaf(m), "s");
    CHECK(strstr(str(m, "a.log"), "3") != NULL);
    CHECK(info(m, "rx").total == 3 && info(m, "rx").missed == 0);
    chasm_free(m);
}

/* Types at load: slots and variables must agree; no value, no compare, no capacity elsewhere. */
static void stream_type_errors(void)
{
    CHECK(strstr(pt_first_error("use test_msgs\ninput rx : double\noutput l : string\noutput n : int\n"
                             "state s {\n do take(rx = rx, log = l, count = n)\n}\n"),
                 "t.chasm:6:15: error: parameter 'rx' of 'take' must be a messages variable, but 'rx' is double") != NULL);
    CHECK(strstr(pt_first_error("use test_msgs\ninput rx : messages\noutput l : messages\noutput n : int\n"
                             "state s {\n do take(rx = rx, log = l, count = n)\n}\n"),
                 "t.chasm:6:25: error: parameter 'log' of 'take' must be a string variable, but 'l' is messages") != NULL);
    CHECK(strstr(pt_first_error("input rx : messages(0)\nstate s {\n}\n"), "t.chasm:1:21: error: the capacity of 'rx' is 0 messages, outside [1, 4096]") != NULL);
    CHECK(strstr(pt_first_error("input rx : messages(4097)\nstate s {\n}\n"), "t.chasm:1:21:") != NULL);
    CHECK(strstr(pt_first_error("input rx : messages(2.5)\nstate s {\n}\n"), "t.chasm:1:21: error: the capacity of 'rx' must be a whole number") != NULL);
    CHECK(strstr(pt_first_error("input rx : double(3)\nstate s {\n}\n"), "t.chasm:1:18: error: only messages variables have a capacity") != NULL);
    CHECK(strstr(pt_first_error("input rx : messages\ntest t : rx > 3\nstate s {\n}\n"), "t.chasm:2:10: error: test 't': 'rx' is a stream of messages") != NULL);
    CHECK(strstr(pt_first_error("var rx : messages\nstate s {\n do set rx = 3\n}\n"), "t.chasm:3:14: error:") != NULL);
    CHECK(strstr(pt_first_error("input rx : messages = 3\nstate s {\n}\n"), "t.chasm:1:23: error:") != NULL);
    /* an input is written by the vehicle: a plugin may not post to it */
    CHECK(strstr(pt_first_error("use test_msgs\ninput rx : messages\nstate s {\n do post(tx = rx)\n}\n"), "t.chasm:4:") != NULL);
    CHECK(strstr(pt_first_error("use test_msgs_badtest\nstate s {\n}\n"), "test handlers may not take messages ('rx')") != NULL);
}

const unit_test stream_tests[] = {
    {"stream_order_two_readers", stream_order_two_readers},
    {"stream_missed_and_capacity", stream_missed_and_capacity},
    {"stream_posts", stream_posts},
    {"stream_host_refusals", stream_host_refusals},
    {"stream_age_and_entry", stream_age_and_entry},
    {"stream_local_relay", stream_local_relay},
    {"stream_hotplug_keeps", stream_hotplug_keeps},
    {"stream_type_errors", stream_type_errors},
    {NULL, NULL},
};
