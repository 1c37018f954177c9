/* A decoded PD0 ensemble as the project's dvl_t.
 *
 * PD0 velocities are the bottom's (bottom track) or the water's (profile)
 * velocity relative to the DVL, in the frame the fixed leader's EX byte
 * says; the vehicle's velocity is their negative. Each frame is brought to
 * RDI's ship axes (X starboard, Y forward along beam 3, Z up), then by the
 * mounting to the body frame (x fwd, y stbd, z down):
 *
 *   beam        the beam-to-instrument matrix of the fixed leader's beam
 *               angle and pattern (convex/concave); with one beam bad and
 *               3-beam solutions allowed (EX bit 1) that beam is solved for
 *               with the error velocity set to zero, as the device would;
 *   instrument  an upward-facing unit's X and Z are negated (RDI adds 180
 *               degrees to its roll), then the heading alignment EA turns it;
 *   ship        as given; if tilts were used (EX bit 2) the device levelled
 *               it, so its pitch and roll are undone;
 *   earth       east, north, up: undone with the variable leader's heading
 *               (the one the device used, its bias EB in it) and, if tilts
 *               were used, its pitch and roll.
 *
 * RDI's attitude matrix M(heading, pitch, roll) takes ship axes to earth;
 * with its own internal pitch sensor (EZ bit 3) the device uses the pitch
 * atan(tan(pitch) cos(roll)), and so do we. */
#include <math.h>
#include <string.h>

#include "auv/auv_dvl_t.h"
#include "drivers/dvl/pd0.h"

#define DEG (M_PI / 180.0)
/* Fewer beams on the bottom than this and there is no altitude: one beam's
 * range is a rock or a fish as often as the seabed. */
#define ALTITUDE_MIN_BEAMS 3

void pd0_mounting_default(pd0_mounting *m)
{
    memset(m, 0, sizeof *m);
    m->velocity_sigma_mps = 0.01;
}

/* RDI's M: ship axes to earth (east, north, up); angles in radians. */
static void attitude(double h, double p, double r, double M[3][3])
{
    double ch = cos(h), sh = sin(h), cp = cos(p), sp = sin(p), cr = cos(r), sr = sin(r);
    double m[3][3] = {{ch * cr + sh * sp * sr, sh * cp, ch * sr - sh * sp * cr},
                      {-sh * cr + ch * sp * sr, ch * cp, -sh * sr - ch * sp * cr},
                      {-cp * sr, sp, cp * cr}};
    memcpy(M, m, sizeof m);
}

static void mul(const double M[3][3], const double v[3], double out[3])
{
    double o[3];
    for (int i = 0; i < 3; i++)
        o[i] = M[i][0] * v[0] + M[i][1] * v[1] + M[i][2] * v[2];
    memcpy(out, o, sizeof o);
}

static void mul_t(const double M[3][3], const double v[3], double out[3])
{
    double o[3];
    for (int i = 0; i < 3; i++)
        o[i] = M[0][i] * v[0] + M[1][i] * v[1] + M[2][i] * v[2];
    memcpy(out, o, sizeof o);
}

/* The pitch and roll the device's transforms use [rad]. */
static void tilts(const pd0_ensemble *e, double *p, double *r)
{
    *r = e->roll_deg * DEG;
    *p = e->pitch_deg * DEG;
    if (e->sensor_source & 0x08)
        *p = atan(tan(*p) * cos(*r));
}

/* Instrument axes to ship axes: facing up, then the heading alignment. */
static void inst_to_ship(const pd0_ensemble *e, const double inst[3], double ship[3])
{
    double v[3] = {inst[0], inst[1], inst[2]};
    if (e->facing_up) {
        v[0] = -v[0];
        v[2] = -v[2];
    }
    double A[3][3];
    attitude(e->heading_alignment_deg * DEG, 0, 0, A);
    mul(A, v, ship);
}

/* Beam velocities to instrument X, Y, Z and error; 0 if too few are good. */
static int beam_to_inst(const pd0_ensemble *e, const double b_in[4], double inst[3], double *err, int *n_good)
{
    double b[4];
    int bad = -1, nbad = 0;
    for (int i = 0; i < 4; i++) {
        b[i] = b_in[i];
        if (isnan(b[i])) {
            bad = i;
            nbad++;
        }
    }
    *n_good = 4 - nbad;
    if (nbad > 1 || (nbad == 1 && !e->three_beam))
        return 0;
    /* the error velocity is d (b1 + b2 - b3 - b4): zero it to solve for the bad beam */
    switch (bad) {
    case 0: b[0] = b[2] + b[3] - b[1]; break;
    case 1: b[1] = b[2] + b[3] - b[0]; break;
    case 2: b[2] = b[0] + b[1] - b[3]; break;
    case 3: b[3] = b[0] + b[1] - b[2]; break;
    default: break;
    }
    double th = e->beam_angle_deg * DEG, c = e->convex ? 1.0 : -1.0;
    double a = 1.0 / (2.0 * sin(th)), bb = 1.0 / (4.0 * cos(th)), d = a / sqrt(2.0);
    inst[0] = c * a * (b[0] - b[1]);
    inst[1] = c * a * (b[3] - b[2]);
    inst[2] = bb * (b[0] + b[1] + b[2] + b[3]);
    *err = nbad ? 0.0 : d * (b[0] + b[1] - b[2] - b[3]);
    return 1;
}

static void ship_to_body(const pd0_mounting *m, const double ship[3], double body[3])
{
    /* RDI ship axes as the body's, mounted straight: x = Y, y = X, z = -Z */
    double v[3] = {ship[1], ship[0], -ship[2]};
    /* then the DVL's rotation from the body (ZYX): body = Rz Ry Rx v */
    double cy = cos(m->yaw_rad), sy = sin(m->yaw_rad), cp = cos(m->pitch_rad), sp = sin(m->pitch_rad);
    double cr = cos(m->roll_rad), sr = sin(m->roll_rad);
    double R[3][3] = {{cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr},
                      {sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr},
                      {-sp, cp * sr, cp * cr}};
    mul(R, v, body);
}

int pd0_body_velocity(const pd0_ensemble *e, const pd0_mounting *m, const double v4[4], double body[3],
                      double *err_mps)
{
    double v[3], ship[3], M[3][3], p = 0, r = 0;
    *err_mps = 0.0;
    switch (e->frame) {
    case PD0_FRAME_BEAM: {
        int n_good;
        /* beams 1-4, the Janus four, whatever the leader's count (a beam left
         * out is marked invalid: the 3-beam solution, where allowed) */
        if (!beam_to_inst(e, v4, v, err_mps, &n_good))
            return 0;
        inst_to_ship(e, v, ship);
        break;
    }
    case PD0_FRAME_INSTRUMENT:
    case PD0_FRAME_SHIP:
    case PD0_FRAME_EARTH:
        if (isnan(v4[0]) || isnan(v4[1]) || isnan(v4[2]))
            return 0;
        memcpy(v, v4, sizeof v);
        *err_mps = isnan(v4[3]) ? 0.0 : v4[3];
        if (e->frame == PD0_FRAME_INSTRUMENT) {
            inst_to_ship(e, v, ship);
        } else {
            if (e->tilts_used)
                tilts(e, &p, &r);
            attitude(e->frame == PD0_FRAME_EARTH ? e->heading_deg * DEG : 0.0, p, r, M);
            mul_t(M, v, ship);
        }
        break;
    default: return 0;
    }
    ship_to_body(m, ship, body);
    for (int i = 0; i < 3; i++)
        body[i] = -body[i]; /* the bottom's (water's) motion relative to the DVL is minus the vehicle's */
    return 1;
}

/* A beam's slant range: PD0's BT range is the vertical range the device
 * computed as slant x cos(beam angle), with no pitch or roll in it (RDI's
 * definition), so the slant is the range over cos(beam angle). */
static double slant_range(const pd0_ensemble *e, int b)
{
    return e->bt_range_m[b] / cos(e->beam_angle_deg * DEG);
}

/* Each beam's slant range times the downward component of the beam (its unit
 * vector in instrument axes, turned to ship axes, then by the device's pitch
 * and roll): the height above a flat seabed seen along that beam. Level, that
 * is PD0's BT range itself. The mean over the beams on the bottom. */
double pd0_altitude(const pd0_ensemble *e)
{
    if (!e->has_bottom_track)
        return -1.0;
    double th = e->beam_angle_deg * DEG, s = sin(th) * (e->convex ? 1.0 : -1.0), c = cos(th);
    const double beam[4][3] = {{-s, 0, -c}, {s, 0, -c}, {0, s, -c}, {0, -s, -c}};
    double p, r, M[3][3];
    tilts(e, &p, &r);
    attitude(0.0, p, r, M);
    double sum = 0;
    int n = 0;
    for (int b = 0; b < 4; b++) {
        if (!(e->bt_range_m[b] > 0))
            continue;
        double ship[3], earth[3];
        inst_to_ship(e, beam[b], ship);
        mul(M, ship, earth);
        if (earth[2] >= -0.05) /* a beam at the horizon or above sees no seabed below */
            continue;
        sum += slant_range(e, b) * -earth[2];
        n++;
    }
    return n >= ALTITUDE_MIN_BEAMS ? sum / n : -1.0;
}

/* Water track: the mean over the profile's cells whose velocity is good. */
static int water_track(const pd0_ensemble *e, const pd0_mounting *m, double body[3], double *err)
{
    if (!e->has_velocity)
        return 0;
    double sum[3] = {0, 0, 0}, esum = 0;
    int n = 0;
    for (int c = 0; c < e->n_cells; c++) {
        double v[3], er;
        if (!pd0_body_velocity(e, m, e->velocity_mps[c], v, &er))
            continue;
        for (int i = 0; i < 3; i++)
            sum[i] += v[i];
        esum += er;
        n++;
    }
    if (!n)
        return 0;
    for (int i = 0; i < 3; i++)
        body[i] = sum[i] / n;
    *err = esum / n;
    return 1;
}

void pd0_to_dvl(const pd0_ensemble *e, const pd0_mounting *m, auv_dvl_t *out)
{
    double v[3] = {0, 0, 0}, err = 0;
    out->mode = AUV_DVL_T_MODE_NONE;
    if (e->has_bottom_track && pd0_body_velocity(e, m, e->bt_velocity_mps, v, &err))
        out->mode = AUV_DVL_T_MODE_BOTTOM_LOCK;
    else if (water_track(e, m, v, &err))
        out->mode = AUV_DVL_T_MODE_WATER_TRACK;
    if (out->mode == AUV_DVL_T_MODE_NONE) {
        v[0] = v[1] = v[2] = err = 0.0;
        out->velocity_sigma_mps = -1.0;
    } else {
        out->velocity_sigma_mps = m->velocity_sigma_mps;
    }
    memcpy(out->velocity_mps, v, sizeof v);
    out->error_velocity_mps = err;
    out->altitude_m = pd0_altitude(e);
    for (int b = 0; b < 4; b++)
        out->beam_range_m[b] = e->has_bottom_track && e->bt_range_m[b] > 0 ? (float)slant_range(e, b) : -1.0f;
    static const int8_t frames[4] = {AUV_DVL_T_FRAME_BEAM, AUV_DVL_T_FRAME_INSTRUMENT, AUV_DVL_T_FRAME_SHIP,
                                     AUV_DVL_T_FRAME_EARTH};
    out->device_frame = frames[e->frame & 3];
    out->ensemble = e->ensemble_number;
    out->device_utime = pd0_rtc_utime(&e->rtc);
    out->has_environment = 1;
    out->temperature_c = e->temperature_c;
    out->salinity = e->salinity_ppt;
    out->sound_speed_mps = e->sound_speed_mps;
}
