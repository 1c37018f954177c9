/* auv-gps: NMEA 0183 GNSS receivers (docs/drivers.md, "auv-gps"). GGA, RMC,
 * VTG, GSA and ZDA from the GP, GN, GL, GA (and GB, BD, GQ, GI) talkers,
 * grouped into one gps_fix_t per epoch on <VEHICLE>.GPS. */
#ifndef DRV_GPS_H
#define DRV_GPS_H

#include <stddef.h>
#include <stdint.h>

#include "drivers/common/drv_protocol.h"
#include "drivers/common/nmea.h"

extern const drv_protocol gps_protocol;

/* ---- one sentence's values (gps_sentence.c) */
typedef enum { GPS_GGA = 1, GPS_RMC = 2, GPS_VTG = 4, GPS_GSA = 8, GPS_ZDA = 16, GPS_OTHER = 0 } gps_kind;

typedef struct {
    gps_kind kind;
    int has_time;
    double tod;     /* UTC seconds of the day */
    int has_pos;
    double lat, lon;
    int quality;    /* GGA fix quality, or RMC's from its status and mode */
    int sats;       /* -1 unknown */
    double hdop, vdop, pdop, alt_m, speed_mps, course_deg; /* NaN unknown */
    int has_date;
    int64_t day;    /* Unix day number */
    int fix_mode;   /* GSA: 1 none, 2 2D, 3 3D; 0 unknown */
} gps_values;

/* Decodes one checked sentence. Returns NULL with *v filled, or the reason it
 * is refused ("bad latitude", "date out of range", ...), detail in why.
 * Sentences that are not GNSS fixes (GSV, TXT, another talker's) are
 * GPS_OTHER: not refused, not used. */
const char *gps_decode(const nmea_sentence *s, int min_year, gps_values *v, char *why, size_t whylen);

/* ---- the driver's state (gps_epoch.c, gps_protocol.c) */
typedef struct {
    int open, published;
    double tod;         /* the epoch's UTC time of day */
    int64_t stamp;      /* receive time of its first sentence */
    unsigned have;      /* GPS_GGA | GPS_RMC seen in it */
    gps_values gga, rmc;
} gps_epoch;

typedef struct {
    /* settings (flags) */
    int have_origin;
    double lat0, lon0, dlat, dlon; /* degrees per metre north and east (python/sim/geo.py) */
    int min_year;
    double uere_m;
    double epoch_timeout_s;
    int64_t last_rx;    /* receive time of the newest bytes: an epoch closes on quiet */
    int settings_done;

    nmea_framer framer;
    nmea_sentence sentence;
    uint64_t garbage_seen;
    int in_garbage;
    int seen_checksum;  /* this receiver checksums its sentences: it is held to it */

    gps_epoch ep;
    unsigned expect;    /* the timed sentences the receiver sent in its last epoch */
    int have_closed;
    double closed_tod;  /* the last epoch closed: its late sentences are not a new epoch */
    int have_date;
    int64_t date_day;   /* the newest date (RMC, ZDA) */
    double date_tod;    /* and the time of day it came with */
    gps_values gsa, vtg;
    int64_t gsa_stamp, vtg_stamp; /* -1 none */
    const auv_type_entry_t *fix_type;
} gps_state;

/* Flag setters (also for tests): --origin LAT,LON, --min-year Y, --uere M,
 * --epoch-timeout S. */
int gps_set_origin(void *state, const char *v, char *err, size_t n);
int gps_set_min_year(void *state, const char *v, char *err, size_t n);
int gps_set_uere(void *state, const char *v, char *err, size_t n);
int gps_set_epoch_timeout(void *state, const char *v, char *err, size_t n);

/* The epoch logic: a decoded sentence received at stamp; time passing. */
void gps_epoch_sentence(gps_state *g, drv_ctx *ctx, const gps_values *v, int64_t stamp);
void gps_epoch_tick(gps_state *g, drv_ctx *ctx, int64_t now);
void gps_epoch_close(gps_state *g, drv_ctx *ctx);
/* Flat-earth NED of a position, as python/sim/geo.py LocalFrame.to_ned. */
void gps_to_ned(const gps_state *g, double lat, double lon, double *north, double *east);

#endif
