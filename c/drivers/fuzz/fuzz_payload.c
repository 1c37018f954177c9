/* Fuzz entry point for auv-payload (c/drivers/payload): any bytes, in reads
 * cut by the input itself, with silences that cut frames, through the
 * driver's protocol. Every message it publishes must be one of its table's
 * topics, decode strictly as that topic's type, and carry a frame whose CRC
 * and length checked (libFuzzer, or c/chasm/fuzz/fuzz_driver.c). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "common/lcm_rx.h"
#include "drivers/payload/payload.h"

static void check(int ok, const char *what)
{
    if (!ok) {
        fprintf(stderr, "fuzz_payload: broken: %s\n", what);
        abort();
    }
}

static void sink(void *user, const char *channel, const auv_type_entry_t *type, const void *data, int len)
{
    (void)user;
    check(!strncmp(channel, "FUZZ.", 5), "a channel of the vehicle");
    int k = 0;
    while (payload_topics[k].topic && strcmp(payload_topics[k].topic, channel + 5) != 0)
        k++;
    check(payload_topics[k].topic != NULL, "a topic of the table");
    check(type == auv_type_find(payload_topics[k].type_name), "the topic's type");
    check(len > 0 && len <= LCMFRAME_MAX_PAYLOAD, "a bounded payload");
    _Alignas(16) uint8_t msg[PAYLOAD_SCRATCH];
    check(rx_decode(type, data, len, msg) == 0, "a published message decodes");
    type->info()->decode_cleanup(msg);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    payload_state *s = calloc(1, sizeof *s);
    drv_ctx ctx;
    drv_ctx_init(&ctx, "fuzz_payload", "FUZZ", "PAYLOAD", sink, NULL);
    ctx.quiet = 1;
    check(s && payload_protocol.init(s, &ctx) == 0, "init");
    int64_t t = INT64_C(1700000000000000);
    unsigned cut = size ? data[0] : 5;
    for (size_t i = 0; i < size;) {
        size_t n = 1 + (cut + i) % 97;
        if (n > size - i)
            n = size - i;
        t += (data[i] & 0x0F) == 0x0F ? 1000000 : 1000; /* now and then a silence past the timeout */
        payload_protocol.tick(s, &ctx, t);
        payload_protocol.feed(s, &ctx, data + i, n, t);
        i += n;
    }
    check(ctx.frames_decoded == ctx.messages_published, "one message per good frame");
    check(s->framer.len <= LCMFRAME_MAX && s->framer.again_len <= LCMFRAME_MAX, "bounded buffers");
    free(s);
    return 0;
}
