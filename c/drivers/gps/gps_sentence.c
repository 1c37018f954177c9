/* One NMEA sentence of a GNSS receiver into its values, strictly: a field
 * that is malformed or outside what a receiver can mean refuses the whole
 * sentence with a reason (a checksum proves only that the bytes arrived as
 * sent, not that the receiver was sane). An empty field is "no value". */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "drivers/gps/gps.h"

#define KNOT_MPS (1852.0 / 3600.0)
/* beyond these no receiver on a vehicle reports a true value */
#define MAX_ALTITUDE_M 20000.0
#define MIN_ALTITUDE_M -1000.0
#define MAX_SPEED_KN 1000.0
#define MAX_DOP 100.0

/* The talkers whose GGA, RMC, VTG, GSA and ZDA are a GNSS receiver's: the
 * constellations (GPS, GLONASS, Galileo, BeiDou as GB and as the older BD,
 * QZSS as GQ and as the older QZ, NavIC), the combined GN, and the
 * integrated navigation and instrumentation talkers IN and II, through which
 * a chart plotter or an echo sounder relays its receiver's fixes. The same
 * sentences from any other talker are valid NMEA but not a position source
 * of ours: ignored, not refused. */
static int gnss_talker(const char *t)
{
    static const char *const talkers[] = {"GP", "GN", "GL", "GA", "GB", "BD", "GQ", "QZ", "GI", "IN", "II"};
    for (size_t i = 0; i < sizeof talkers / sizeof talkers[0]; i++)
        if (!strcmp(t, talkers[i]))
            return 1;
    return 0;
}

#define REFUSE(reason, ...)                    \
    do {                                       \
        snprintf(why, whylen, __VA_ARGS__);    \
        return reason;                         \
    } while (0)

/* A double field within [lo, hi]: 1 value, 0 empty, -1 refused. */
static int ranged(const nmea_sentence *s, int i, double lo, double hi, double *out)
{
    int r = nmea_field_double(s, i, out);
    if (r == 1 && !(*out >= lo && *out <= hi))
        return -1;
    return r;
}

static const char *position(const nmea_sentence *s, int i, gps_values *v, char *why, size_t whylen)
{
    int a = nmea_field_latitude(s, i, &v->lat), b = nmea_field_longitude(s, i + 2, &v->lon);
    if (a < 0)
        REFUSE("bad latitude", "%s: latitude '%s%s'", s->text, s->field[i], i + 1 < s->nfields ? s->field[i + 1] : "");
    if (b < 0)
        REFUSE("bad longitude", "%s: longitude '%s%s'", s->text, s->field[i + 2],
               i + 3 < s->nfields ? s->field[i + 3] : "");
    if (a != b)
        REFUSE("missing position", "%s: a latitude without a longitude or back", s->text);
    v->has_pos = a == 1;
    return NULL;
}

static const char *time_of_day(const nmea_sentence *s, int i, gps_values *v, char *why, size_t whylen)
{
    int r = nmea_field_time_of_day(s, i, &v->tod);
    if (r < 0)
        REFUSE("bad time", "%s: time '%s'", s->text, s->field[i]);
    v->has_time = r == 1;
    return NULL;
}

static const char *date_check(const nmea_sentence *s, int64_t day, int min_year, char *why, size_t whylen)
{
    /* a receiver that has lost its almanac, or one past a GPS week rollover,
     * sends a checksummed date decades off: refused, not believed */
    if (day < nmea_unix_day(min_year, 1, 1))
        REFUSE("date out of range", "%s: a date before %d (--min-year)", s->text, min_year);
    return NULL;
}

/* A sentence that says "no fix" (GGA quality 0, RMC status V) carries
 * whatever its receiver keeps before a fix: MTK's 8960.0000 N (89 deg 60 min),
 * 36000.0000 N, 1980's date. Nothing of it is used, so nothing of it is
 * refused: only its time of day is kept, and its date if the date is sane.
 * (Framing, checksum, the quality or status field itself are still checked.) */
static void no_fix(const nmea_sentence *s, int time_field, int date_field, int min_year, gps_values *v)
{
    v->has_time = nmea_field_time_of_day(s, time_field, &v->tod) == 1;
    v->has_pos = 0;
    v->quality = 0;
    if (date_field >= 0 && v->has_time && nmea_field_date_ddmmyy(s, date_field, &v->day) == 1 &&
        v->day >= nmea_unix_day(min_year, 1, 1))
        v->has_date = 1;
}

static const char *gga(const nmea_sentence *s, int min_year, gps_values *v, char *why, size_t whylen)
{
    const char *r;
    long q, n;
    if (s->nfields < 9)
        REFUSE("too few fields", "%s: %d fields, GGA has 14", s->text, s->nfields);
    int qr = nmea_field_int(s, 5, &q);
    if (qr < 0 || (qr == 1 && (q < 0 || q > 8)))
        REFUSE("bad fix quality", "%s: fix quality '%s' (0 .. 8)", s->text, s->field[5]);
    /* 0: no fix; 8: the receiver's simulator (a demonstration's position,
     * which its RMC marks V); a satellite fix (1..5) from no satellite: a
     * receiver coasting on its last fix (Hemisphere's "1,00"). None is a fix. */
    long sats0;
    int zero_sats = nmea_field_int(s, 6, &sats0) == 1 && sats0 == 0;
    if (qr == 0 || q == 0 || q == 8 || (q <= 5 && zero_sats)) {
        no_fix(s, 0, -1, min_year, v);
        return NULL;
    }
    if ((r = time_of_day(s, 0, v, why, whylen)) || (r = position(s, 1, v, why, whylen)))
        return r;
    v->quality = (int)q;
    int nr = nmea_field_int(s, 6, &n);
    if (nr < 0 || (nr == 1 && (n < 0 || n > 99)))
        REFUSE("bad satellites", "%s: satellites '%s' (0 .. 99)", s->text, s->field[6]);
    v->sats = nr == 1 ? (int)n : -1;
    if (ranged(s, 7, 0.0, MAX_DOP, &v->hdop) < 0)
        REFUSE("bad hdop", "%s: HDOP '%s'", s->text, s->field[7]);
    if (ranged(s, 8, MIN_ALTITUDE_M, MAX_ALTITUDE_M, &v->alt_m) < 0 ||
        (s->field[8][0] && s->nfields > 9 && strcmp(s->field[9], "M") != 0))
        REFUSE("bad altitude", "%s: altitude '%s'", s->text, s->field[8]);
    if (v->quality > 0 && !v->has_pos)
        REFUSE("missing position", "%s: fix quality %d without a position", s->text, v->quality);
    if (v->quality > 0 && !v->has_time)
        REFUSE("bad time", "%s: a fix without its time", s->text);
    return NULL;
}

/* RMC's mode indicator (NMEA 2.3 on) as a GGA quality; 'N' (no fix), 'S'
 * (simulator) and 'V' (not valid, some receivers' spelling of it) are 0; another capital
 * letter, a mode of a later version or a maker's, is left to the status
 * field (-2); anything else is malformed (-1). */
static int mode_quality(char m)
{
    switch (m) {
    case 'A': return 1;
    case 'D': return 2;
    case 'P': return 3;
    case 'R': return 4;
    case 'F': return 5;
    case 'E': return 6;
    case 'M': return 7;
    case 'S': return 0; /* the receiver's simulator: no fix of the vehicle's */
    case 'N': return 0;
    case 'V': return 0;
    default: return m >= 'A' && m <= 'Z' ? -2 : -1;
    }
}

static const char *rmc(const nmea_sentence *s, int min_year, gps_values *v, char *why, size_t whylen)
{
    const char *r;
    if (!s->checksummed) /* NMEA 0183 2.0 on: RMC's checksum is mandatory */
        REFUSE("no checksum", "%s: an RMC without its checksum", s->text);
    if (s->nfields < 9)
        REFUSE("too few fields", "%s: %d fields, RMC has 11 or more", s->text, s->nfields);
    const char *st = s->field[1];
    if (strcmp(st, "A") != 0 && strcmp(st, "V") != 0)
        REFUSE("bad status", "%s: status '%s' (A or V)", s->text, st);
    if (st[0] == 'V') {
        no_fix(s, 0, 8, min_year, v);
        return NULL;
    }
    if ((r = time_of_day(s, 0, v, why, whylen)) || (r = position(s, 2, v, why, whylen)))
        return r;
    v->quality = 1;
    if (s->nfields > 11 && s->field[11][0]) {
        int q = s->field[11][1] ? -1 : mode_quality(s->field[11][0]);
        if (q == -1)
            REFUSE("bad mode", "%s: mode '%s'", s->text, s->field[11]);
        if (v->quality && q != -2)
            v->quality = q;
    }
    double kn;
    int sr = ranged(s, 6, 0.0, MAX_SPEED_KN, &kn);
    if (sr < 0)
        REFUSE("bad speed", "%s: speed '%s' kn", s->text, s->field[6]);
    v->speed_mps = sr == 1 ? kn * KNOT_MPS : NAN;
    if (ranged(s, 7, 0.0, 360.0, &v->course_deg) < 0)
        REFUSE("bad course", "%s: course '%s'", s->text, s->field[7]);
    if (v->course_deg == 360.0)
        v->course_deg = 0.0;
    int dr = nmea_field_date_ddmmyy(s, 8, &v->day);
    if (dr < 0)
        REFUSE("bad date", "%s: date '%s'", s->text, s->field[8]);
    if (dr == 1 && (r = date_check(s, v->day, min_year, why, whylen)))
        return r;
    v->has_date = dr == 1 && v->has_time;
    if (v->quality > 0 && (!v->has_pos || !v->has_time))
        REFUSE("missing position", "%s: status A without a position or time", s->text);
    return NULL;
}

/* VTG of NMEA 0183 before 2.0: course true, course magnetic, knots, km/h,
 * without the unit letters (four fields). */
static const char *vtg_v1(const nmea_sentence *s, gps_values *v, char *why, size_t whylen)
{
    double kn, kmh;
    if (ranged(s, 0, 0.0, 360.0, &v->course_deg) < 0)
        REFUSE("bad course", "%s: course '%s'", s->text, s->field[0]);
    if (v->course_deg == 360.0)
        v->course_deg = 0.0;
    int a = ranged(s, 2, 0.0, MAX_SPEED_KN, &kn), b = ranged(s, 3, 0.0, MAX_SPEED_KN * 1.852, &kmh);
    if (a < 0 || b < 0)
        REFUSE("bad speed", "%s: speed '%s' kn, '%s' km/h", s->text, s->field[2], s->field[3]);
    v->speed_mps = a == 1 ? kn * KNOT_MPS : b == 1 ? kmh / 3.6 : NAN;
    return NULL;
}

static const char *vtg(const nmea_sentence *s, gps_values *v, char *why, size_t whylen)
{
    if (s->nfields == 4 && strcmp(s->field[1], "T") != 0)
        return vtg_v1(s, v, why, whylen);
    if (s->nfields < 8)
        REFUSE("too few fields", "%s: %d fields, VTG has 8 or more", s->text, s->nfields);
    if (ranged(s, 0, 0.0, 360.0, &v->course_deg) < 0 || (s->field[0][0] && strcmp(s->field[1], "T") != 0))
        REFUSE("bad course", "%s: course '%s'", s->text, s->field[0]);
    if (v->course_deg == 360.0)
        v->course_deg = 0.0;
    double kn, kmh;
    int a = ranged(s, 4, 0.0, MAX_SPEED_KN, &kn), b = ranged(s, 6, 0.0, MAX_SPEED_KN * 1.852, &kmh);
    if (a < 0 || b < 0)
        REFUSE("bad speed", "%s: speed '%s' kn, '%s' km/h", s->text, s->field[4], s->field[6]);
    v->speed_mps = a == 1 ? kn * KNOT_MPS : b == 1 ? kmh / 3.6 : NAN;
    if (s->nfields > 8 && !strcmp(s->field[8], "N")) /* mode: data not valid */
        v->speed_mps = v->course_deg = NAN;
    return NULL;
}

/* GSA: selection mode, fix mode, 12 satellites, PDOP, HDOP, VDOP (and NMEA
 * 4.11's system id). Without a fix some receivers cut it short after the
 * fix mode ("$GPGSA,A,1,,,,*32"): that is a fix mode and no DOPs. */
static const char *gsa(const nmea_sentence *s, gps_values *v, char *why, size_t whylen)
{
    long m;
    if (s->nfields < 2)
        REFUSE("too few fields", "%s: %d fields, GSA has 17 or more", s->text, s->nfields);
    int mr = nmea_field_int(s, 1, &m);
    if (mr < 0 || (mr == 1 && (m < 1 || m > 3)))
        REFUSE("bad fix mode", "%s: fix mode '%s' (1 .. 3)", s->text, s->field[1]);
    v->fix_mode = mr == 1 ? (int)m : 0;
    if (s->nfields < 17 && v->fix_mode != 1)
        REFUSE("too few fields", "%s: %d fields, GSA has 17 or more", s->text, s->nfields);
    if (s->nfields < 17)
        return NULL;
    if (ranged(s, 14, 0.0, MAX_DOP, &v->pdop) < 0 || ranged(s, 15, 0.0, MAX_DOP, &v->hdop) < 0 ||
        ranged(s, 16, 0.0, MAX_DOP, &v->vdop) < 0)
        REFUSE("bad dop", "%s: PDOP '%s', HDOP '%s', VDOP '%s'", s->text, s->field[14], s->field[15], s->field[16]);
    return NULL;
}

static const char *zda(const nmea_sentence *s, int min_year, gps_values *v, char *why, size_t whylen)
{
    const char *r;
    long d, mo, y;
    if (s->nfields < 4)
        REFUSE("too few fields", "%s: %d fields, ZDA has 6", s->text, s->nfields);
    if ((r = time_of_day(s, 0, v, why, whylen)))
        return r;
    int a = nmea_field_int(s, 1, &d), b = nmea_field_int(s, 2, &mo), c = nmea_field_int(s, 3, &y);
    if (a == 0 && b == 0 && c == 0)
        return NULL; /* no date yet */
    if (a != 1 || b != 1 || c != 1 || strlen(s->field[3]) != 4 || d > 31 || mo > 12 || y > 2099)
        REFUSE("bad date", "%s: date '%s-%s-%s'", s->text, s->field[3], s->field[2], s->field[1]);
    v->day = nmea_unix_day((int)y, (int)mo, (int)d);
    if (v->day < 0)
        REFUSE("bad date", "%s: date '%s-%s-%s'", s->text, s->field[3], s->field[2], s->field[1]);
    if ((r = date_check(s, v->day, min_year, why, whylen)))
        return r;
    v->has_date = v->has_time;
    return NULL;
}

const char *gps_decode(const nmea_sentence *s, int min_year, gps_values *v, char *why, size_t whylen)
{
    memset(v, 0, sizeof *v);
    v->sats = -1;
    v->hdop = v->vdop = v->pdop = v->alt_m = v->speed_mps = v->course_deg = NAN;
    v->lat = v->lon = NAN;
    static const struct {
        const char *type;
        gps_kind kind;
    } kinds[] = {{"GGA", GPS_GGA}, {"RMC", GPS_RMC}, {"VTG", GPS_VTG}, {"GSA", GPS_GSA}, {"ZDA", GPS_ZDA}};
    v->kind = GPS_OTHER;
    for (size_t i = 0; i < sizeof kinds / sizeof kinds[0]; i++)
        if (!strcmp(s->type, kinds[i].type))
            v->kind = kinds[i].kind;
    if (v->kind == GPS_OTHER)
        return NULL;
    if (!gnss_talker(s->talker)) {
        v->kind = GPS_OTHER; /* valid, not a receiver's: ignored (above) */
        return NULL;
    }
    switch (v->kind) {
    case GPS_GGA: return gga(s, min_year, v, why, whylen);
    case GPS_RMC: return rmc(s, min_year, v, why, whylen);
    case GPS_VTG: return vtg(s, v, why, whylen);
    case GPS_GSA: return gsa(s, v, why, whylen);
    case GPS_ZDA: return zda(s, min_year, v, why, whylen);
    default: return NULL;
    }
}
