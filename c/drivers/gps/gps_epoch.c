/* One fix per epoch. A receiver sends a burst of sentences per epoch; those
 * that carry a time (GGA, RMC) belong to the epoch of that UTC time of day.
 * The fix is published as soon as the epoch holds every timed sentence the
 * receiver sent in its previous epoch (GGA and RMC, or only the one it
 * sends), else when a sentence of another time arrives, or when the line has
 * been quiet --epoch-timeout seconds (the burst ended without it: a sentence
 * lost to a bad checksum). Quiet, not open: at 9600 baud a receiver's burst
 * of GGA, GSA, a dozen GSV and RMC takes most of a second, and a timeout from
 * the epoch's first sentence would publish it before its RMC came.
 * GSA and VTG carry no time: the newest of each, if received within
 * AUX_MAX_AGE of the epoch, lends its DOPs, fix mode and speed (GSA usually
 * follows GGA, so a fix takes the previous epoch's DOPs: they change slowly).
 * An epoch without a valid position (no fix yet) publishes nothing, as the
 * simulator's GPS says nothing under water. */
#include <math.h>
#include <string.h>

#include "auv/auv_gps_fix_t.h"
#include "drivers/gps/gps.h"

#define AUX_MAX_AGE_US INT64_C(2000000)
#define NO_HDOP_FACTOR 5.0  /* no HDOP at all: a conservative sigma */
#define MIN_HDOP_FACTOR 0.5 /* HDOP 0 is no reason to trust a fix infinitely */

void gps_to_ned(const gps_state *g, double lat, double lon, double *north, double *east)
{
    if (!g->have_origin) {
        *north = *east = NAN;
        return;
    }
    *north = (lat - g->lat0) / g->dlat;
    *east = (lon - g->lon0) / g->dlon;
}

static int recent(int64_t aux_stamp, int64_t epoch_stamp)
{
    return aux_stamp >= 0 && epoch_stamp - aux_stamp <= AUX_MAX_AGE_US;
}

/* The UTC of a time of day from the newest date, across midnight: a time of
 * day half a day away from the date's own belongs to the next (or previous)
 * day. -1 without a date. */
static int64_t utc_us(const gps_state *g, double tod)
{
    if (!g->have_date)
        return -1;
    double t = (double)g->date_day * 86400.0 + tod, ref = (double)g->date_day * 86400.0 + g->date_tod;
    if (t < ref - 43200.0)
        t += 86400.0;
    else if (t > ref + 43200.0)
        t -= 86400.0;
    return (int64_t)llround(t * 1e6);
}

static void publish(gps_state *g, drv_ctx *ctx)
{
    gps_epoch *e = &g->ep;
    e->published = 1;
    const gps_values *pos = NULL;
    if ((e->have & GPS_GGA) && e->gga.quality > 0 && e->gga.has_pos)
        pos = &e->gga;
    else if ((e->have & GPS_RMC) && e->rmc.quality > 0 && e->rmc.has_pos)
        pos = &e->rmc;
    if (!pos)
        return;
    int gsa_ok = recent(g->gsa_stamp, e->stamp), vtg_ok = recent(g->vtg_stamp, e->stamp);
    auv_gps_fix_t m;
    memset(&m, 0, sizeof m);
    m.utime = e->stamp;
    m.vehicle = (char *)ctx->vehicle;
    m.latitude_deg = pos->lat;
    m.longitude_deg = pos->lon;
    gps_to_ned(g, pos->lat, pos->lon, &m.north_m, &m.east_m);
    m.quality = (int8_t)pos->quality;
    m.satellites = (int16_t)((e->have & GPS_GGA) ? e->gga.sats : -1);
    m.altitude_m = (e->have & GPS_GGA) ? e->gga.alt_m : NAN;
    m.hdop = (e->have & GPS_GGA) && !isnan(e->gga.hdop) ? e->gga.hdop : gsa_ok ? g->gsa.hdop : NAN;
    m.pdop = gsa_ok ? g->gsa.pdop : NAN;
    m.vdop = gsa_ok ? g->gsa.vdop : NAN;
    if (gsa_ok && g->gsa.fix_mode >= 2)
        m.fix_type = g->gsa.fix_mode == 2 ? AUV_GPS_FIX_T_FIX_2D : AUV_GPS_FIX_T_FIX_3D;
    else
        m.fix_type = isnan(m.altitude_m) ? AUV_GPS_FIX_T_FIX_2D : AUV_GPS_FIX_T_FIX_3D;
    double f = isnan(m.hdop) ? NO_HDOP_FACTOR : m.hdop < MIN_HDOP_FACTOR ? MIN_HDOP_FACTOR : m.hdop;
    m.horizontal_sigma_m = g->uere_m * f;
    if ((e->have & GPS_RMC) && !isnan(e->rmc.speed_mps)) {
        m.speed_mps = e->rmc.speed_mps;
        m.course_deg = e->rmc.course_deg;
    } else {
        m.speed_mps = vtg_ok ? g->vtg.speed_mps : NAN;
        m.course_deg = vtg_ok ? g->vtg.course_deg : NAN;
    }
    m.utc_utime = utc_us(g, e->tod);
    drv_publish(ctx, "GPS", g->fix_type, &m);
}

void gps_epoch_close(gps_state *g, drv_ctx *ctx)
{
    if (!g->ep.open)
        return;
    if (!g->ep.published)
        publish(g, ctx);
    g->expect = g->ep.have;
    g->have_closed = 1;
    g->closed_tod = g->ep.tod;
    memset(&g->ep, 0, sizeof g->ep);
}

void gps_epoch_sentence(gps_state *g, drv_ctx *ctx, const gps_values *v, int64_t stamp)
{
    if (v->has_date) {
        g->have_date = 1;
        g->date_day = v->day;
        g->date_tod = v->tod;
    }
    if (v->kind == GPS_GSA) {
        g->gsa = *v;
        g->gsa_stamp = stamp;
        return;
    }
    if (v->kind == GPS_VTG) {
        g->vtg = *v;
        g->vtg_stamp = stamp;
        return;
    }
    if ((v->kind != GPS_GGA && v->kind != GPS_RMC) || !v->has_time)
        return; /* ZDA: its date is kept above; a GGA without time: no fix, no epoch */
    if (g->ep.open && g->ep.tod != v->tod)
        gps_epoch_close(g, ctx);
    if (!g->ep.open && g->have_closed && g->closed_tod == v->tod)
        return; /* a late sentence of an epoch that timed out: already published */
    gps_epoch *e = &g->ep;
    if (!e->open) {
        e->open = 1;
        e->tod = v->tod;
        e->stamp = stamp;
    }
    if (e->published)
        return; /* a late sentence of an epoch already out (or a repeat) */
    e->have |= (unsigned)v->kind;
    if (v->kind == GPS_GGA)
        e->gga = *v;
    else
        e->rmc = *v;
    unsigned expect = g->expect ? g->expect : (GPS_GGA | GPS_RMC);
    if ((e->have & expect) == expect)
        publish(g, ctx);
}

void gps_epoch_tick(gps_state *g, drv_ctx *ctx, int64_t now)
{
    int64_t since = g->last_rx > g->ep.stamp ? g->last_rx : g->ep.stamp;
    if (g->ep.open && !g->ep.published && now - since > (int64_t)(g->epoch_timeout_s * 1e6))
        gps_epoch_close(g, ctx);
}
