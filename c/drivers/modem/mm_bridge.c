/* The Micro-Modem bridge's state machine (mm_bridge.h): one packet of one
 * frame at a time, every wait bounded by a timeout, every refusal and every
 * modem complaint counted with its reason. */
#include "drivers/modem/mm_bridge.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

void mm_options_default(mm_options *o)
{
    memset(o, 0, sizeof *o);
    o->vehicle = "";
    o->kind = 2; /* modem_tx_t.KIND_TEAM: the team link's frames */
    o->cst = 1;
    o->answer_timeout_us = 5000000;
    o->ack_timeout_us = 20000000;
    o->rx_hold_us = 2000000;
}

void mm_out_clear(mm_out *out)
{
    out->n_sentences = 0;
    out->n_frames = 0;
    out->status_changed = 0;
}

static int own(const mm_bridge *b) { return b->status.address; }

static void emit(mm_out *out, const mm_msg *m)
{
    if (out->n_sentences < MM_OUT_SENTENCES && mm_format(m, out->sentence[out->n_sentences], MM_BODY_MAX) > 0)
        out->n_sentences++;
}

static void set_text(char *dst, const char *fmt, va_list ap) { vsnprintf(dst, MM_TEXT_MAX, fmt, ap); }

static void error(mm_bridge *b, mm_out *out, int64_t *counter, const char *fmt, ...) __attribute__((format(printf, 4, 5)));
static void error(mm_bridge *b, mm_out *out, int64_t *counter, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    set_text(b->status.last_error, fmt, ap);
    va_end(ap);
    (*counter)++;
    out->status_changed = 1;
}

static int refuse(mm_bridge *b, mm_out *out, int64_t *counter, int32_t seq, const char *fmt, ...) __attribute__((format(printf, 5, 6)));
static int refuse(mm_bridge *b, mm_out *out, int64_t *counter, int32_t seq, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    set_text(b->status.last_refusal, fmt, ap);
    va_end(ap);
    (*counter)++;
    b->status.last_refused_seq = seq;
    out->status_changed = 1;
    return 1;
}

static void go_idle(mm_bridge *b, mm_out *out)
{
    b->state = MM_IDLE;
    b->status.busy_until_utime = 0;
    out->status_changed = 1;
}

static void wait_for(mm_bridge *b, mm_state s, int64_t deadline)
{
    b->state = s;
    b->deadline_us = deadline;
    b->status.busy_until_utime = deadline;
}

int mm_bridge_init(mm_bridge *b, const mm_options *o, const mm_table *t, const char **why)
{
    memset(b, 0, sizeof *b);
    b->opt = *o;
    b->table = *t;
    b->rx_rate = -1;
    int a = mm_table_address(t, o->vehicle ? o->vehicle : "");
    if (a < 0) {
        *why = "this vehicle is not in the address table";
        return -1;
    }
    if (mm_rate_frames(o->rate) < 0) {
        *why = "unknown rate (the Micro-Modem's are 0..5)";
        return -1;
    }
    if (o->kind < 0 || o->kind > 127 || (o->ack != 0 && o->ack != 1)) {
        *why = "kind is not 0..127 or ack not 0/1";
        return -1;
    }
    if (o->answer_timeout_us <= 0 || o->ack_timeout_us <= 0 || o->rx_hold_us <= 0) {
        *why = "a timeout is not positive";
        return -1;
    }
    b->status.address = a;
    b->status.rate = o->rate;
    return 0;
}

static void cfg(mm_out *out, mm_kind k, const char *name, const char *value)
{
    mm_msg m = {.kind = k};
    snprintf(m.u.cfg.name, sizeof m.u.cfg.name, "%s", name);
    snprintf(m.u.cfg.value, sizeof m.u.cfg.value, "%s", value);
    emit(out, &m);
}

void mm_bridge_start(mm_bridge *b, int64_t now_us, mm_out *out)
{
    (void)now_us;
    char v[8];
    snprintf(v, sizeof v, "%d", own(b));
    cfg(out, MM_CCCFG, "SRC", v);
    cfg(out, MM_CCCFG, "CST", b->opt.cst ? "1" : "0");
    cfg(out, MM_CCCFQ, "SRC", "");
    out->status_changed = 1;
}

int mm_bridge_send(mm_bridge *b, int32_t seq, const char *dst_vehicle, int kind, const uint8_t *payload,
                   int n_bytes, int64_t now_us, mm_out *out)
{
    mm_status *st = &b->status;
    if (kind != b->opt.kind)
        return refuse(b, out, &st->refused_invalid, seq, "kind %d: this Micro-Modem link carries kind %d only", kind,
                      b->opt.kind);
    if (n_bytes <= 0 || !payload)
        return refuse(b, out, &st->refused_invalid, seq, "an empty frame (n_bytes = %d)", n_bytes);
    int dest = MM_BROADCAST;
    if (dst_vehicle && *dst_vehicle) {
        dest = mm_table_address(&b->table, dst_vehicle);
        if (dest < 0)
            return refuse(b, out, &st->refused_invalid, seq, "no modem address for %.32s in the address table",
                          dst_vehicle);
        if (dest == own(b))
            return refuse(b, out, &st->refused_invalid, seq, "a frame addressed to this vehicle");
    }
    int max = mm_rate_frame_bytes(b->opt.rate);
    if (n_bytes > max)
        return refuse(b, out, &st->refused_size, seq, "%d bytes is over rate %d's %d-byte frame", n_bytes,
                      b->opt.rate, max);
    if (b->state != MM_IDLE)
        return refuse(b, out, &st->refused_rate, seq, "busy: frame %d is on its way (%s)", b->seq,
                      b->state == MM_WAIT_DRQ ? "waiting for CADRQ" : b->state == MM_WAIT_ECHO ? "waiting for CATXD"
                                                                                        : "waiting for CAACK");
    b->seq = seq;
    b->dest = dest;
    b->ack = b->opt.ack && dest != MM_BROADCAST; /* nobody acknowledges a broadcast */
    b->n_bytes = n_bytes;
    memcpy(b->payload, payload, (size_t)n_bytes);
    mm_msg m = {.kind = MM_CCCYC};
    m.u.cyc = (mm_cyc){.cmd = 0, .src = own(b), .dest = dest, .rate = b->opt.rate, .ack = b->ack, .nframes = 1};
    emit(out, &m);
    wait_for(b, MM_WAIT_DRQ, now_us + b->opt.answer_timeout_us);
    out->status_changed = 1;
    return 0;
}

static void deliver(mm_bridge *b, mm_out *out, const mm_rx_frame *f)
{
    if (out->n_frames < MM_OUT_FRAMES)
        out->frame[out->n_frames++] = *f;
    b->status.received++;
    out->status_changed = 1;
}

static void flush_held(mm_bridge *b, mm_out *out)
{
    for (int i = 0; i < b->n_held; i++)
        deliver(b, out, &b->held[i]);
    b->n_held = 0;
}

static void on_drq(mm_bridge *b, const mm_drq *d, int64_t now_us, mm_out *out)
{
    mm_msg m = {.kind = MM_CCTXD};
    if (b->state != MM_WAIT_DRQ || d->frame != 1 || d->src != own(b)) {
        /* not our cycle (another modem asked us to send, or a stray request):
         * an empty frame ends the modem's wait at once */
        m.u.data = (mm_data){.src = d->src, .dest = d->dest, .ack = d->ack};
        emit(out, &m);
        return;
    }
    if (b->n_bytes > d->nbytes) {
        m.u.data = (mm_data){.src = d->src, .dest = d->dest, .ack = d->ack};
        emit(out, &m);
        refuse(b, out, &b->status.refused_size, b->seq, "%d bytes is over the %d the modem asked for", b->n_bytes,
               d->nbytes);
        go_idle(b, out);
        return;
    }
    m.u.data = (mm_data){.src = own(b), .dest = b->dest, .ack = b->ack, .n = b->n_bytes};
    memcpy(m.u.data.data, b->payload, (size_t)b->n_bytes);
    emit(out, &m);
    wait_for(b, MM_WAIT_ECHO, now_us + b->opt.answer_timeout_us);
}

static void on_rxd(mm_bridge *b, const mm_data *d, int64_t now_us, mm_out *out)
{
    if (d->n == 0)
        return; /* the sender had nothing for this frame */
    if (d->dest != own(b) && d->dest != MM_BROADCAST) {
        error(b, out, &b->status.rx_dropped, "a frame for address %d (this modem is %d)", d->dest, own(b));
        return;
    }
    const char *src = mm_table_vehicle(&b->table, d->src);
    if (!src) {
        error(b, out, &b->status.rx_dropped, "a frame from address %d, which is not in the address table", d->src);
        return;
    }
    int max = b->rx_rate >= 0 ? mm_rate_frame_bytes(b->rx_rate) : MM_MAX_FRAME_BYTES;
    if (d->n > max) {
        error(b, out, &b->status.rx_dropped, "a %d-byte frame is over rate %d's %d bytes", d->n, b->rx_rate, max);
        return;
    }
    mm_rx_frame f = {.utime = now_us, .kind = b->opt.kind, .snr_db = NAN, .src_address = d->src,
                     .dst_address = d->dest, .rate = b->rx_rate, .n_bytes = d->n};
    snprintf(f.src_vehicle, sizeof f.src_vehicle, "%s", src);
    if (d->dest != MM_BROADCAST)
        snprintf(f.dst_vehicle, sizeof f.dst_vehicle, "%s", b->opt.vehicle);
    memcpy(f.payload, d->data, (size_t)d->n);
    if (!b->opt.cst) {
        deliver(b, out, &f);
        return;
    }
    if (b->n_held == MM_OUT_FRAMES)
        flush_held(b, out);
    if (b->n_held == 0)
        b->held_since_us = now_us;
    b->held[b->n_held++] = f;
}

static void on_cst(mm_bridge *b, const mm_cst *c, mm_out *out)
{
    for (int i = 0; i < b->n_held; i++) {
        b->held[i].snr_db = c->snr_in;
        b->held[i].rate = c->rate;
    }
    flush_held(b, out);
    if (c->nbad > 0) {
        b->status.lost += c->nbad;
        out->status_changed = 1;
    }
    b->rx_rate = -1; /* the packet is over */
}

static void on_cfg(mm_bridge *b, const mm_cfg *c, mm_out *out)
{
    if (strcmp(c->name, "SRC"))
        return;
    int a = -1;
    if (sscanf(c->value, "%d", &a) != 1 || a != own(b))
        error(b, out, &b->status.modem_errors, "the modem's address is %.23s, the address table gives %d", c->value,
              own(b));
}

void mm_bridge_input(mm_bridge *b, const mm_msg *m, int64_t now_us, mm_out *out)
{
    switch (m->kind) {
    case MM_CADRQ:
        on_drq(b, &m->u.drq, now_us, out);
        break;
    case MM_CATXD:
        if (b->state != MM_WAIT_ECHO || m->u.data.src != own(b) || m->u.data.dest != b->dest)
            break;
        b->status.sent++;
        if (b->ack)
            wait_for(b, MM_WAIT_ACK, now_us + b->opt.ack_timeout_us);
        else
            go_idle(b, out);
        out->status_changed = 1;
        break;
    case MM_CAACK:
        /* a third party's ack, or one for a frame we no longer wait for, is not ours */
        if (b->state == MM_WAIT_ACK && m->u.ack.src == b->dest && m->u.ack.dest == own(b) && m->u.ack.frame == 1) {
            b->status.acked++;
            go_idle(b, out);
        }
        break;
    case MM_CAERR:
        error(b, out, &b->status.modem_errors, "CAERR %s %d: %s", m->u.err.module, m->u.err.number, m->u.err.text);
        if (b->state == MM_WAIT_DRQ || b->state == MM_WAIT_ECHO)
            go_idle(b, out); /* the modem gave up this cycle: nothing more will come for it */
        break;
    case MM_CAREV:
        b->status.heartbeat_utime = now_us;
        if (!strcmp(m->u.rev.ident, "INIT")) {
            /* it has just booted: its cycle is gone, and so may be its configuration */
            if (b->state != MM_IDLE)
                error(b, out, &b->status.timeouts, "the modem rebooted during frame %d", b->seq);
            go_idle(b, out);
            mm_bridge_start(b, now_us, out);
        } else if (!strcmp(m->u.rev.ident, "AUV") || !b->status.revision[0]) {
            snprintf(b->status.revision, sizeof b->status.revision, "%s", m->u.rev.version);
        }
        out->status_changed = 1;
        break;
    case MM_CACFG:
        on_cfg(b, &m->u.cfg, out);
        break;
    case MM_CACYC:
        if (m->u.cyc.src != own(b))
            b->rx_rate = m->u.cyc.rate; /* another modem's packet: its frames follow */
        break;
    case MM_CARXD:
        on_rxd(b, &m->u.data, now_us, out);
        break;
    case MM_CACST:
        on_cst(b, &m->u.cst, out);
        break;
    default:
        break;
    }
}

void mm_bridge_flush(mm_bridge *b, mm_out *out) { flush_held(b, out); }

void mm_bridge_tick(mm_bridge *b, int64_t now_us, mm_out *out)
{
    if (b->state != MM_IDLE && now_us >= b->deadline_us) {
        double s = (double)(b->state == MM_WAIT_ACK ? b->opt.ack_timeout_us : b->opt.answer_timeout_us) * 1e-6;
        if (b->state == MM_WAIT_ACK)
            error(b, out, &b->status.ack_timeouts, "no CAACK within %.1f s for frame %d", s, b->seq);
        else
            error(b, out, &b->status.timeouts, "no %s within %.1f s for frame %d",
                  b->state == MM_WAIT_DRQ ? "CADRQ" : "CATXD", s, b->seq);
        go_idle(b, out);
    }
    if (b->n_held > 0 && now_us - b->held_since_us >= b->opt.rx_hold_us)
        flush_held(b, out);
}
