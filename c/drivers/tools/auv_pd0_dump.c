/* auv-pd0-dump: PD0 bytes (a file, or stdin) through the framer and decoder
 * of c/drivers/dvl, one JSON object per line: each ensemble decoded (its
 * leaders, bottom track, first cells and the dvl_t the driver would publish)
 * or refused (its reason), then a summary (garbage bytes, continuity). The
 * tests compare it with the simulator's emulator and with dolfyn; at sea it
 * decodes a recorded wire again.
 *
 *   auv-pd0-dump [--chunk N] [--mount-yaw-deg A] [--mount-pitch-deg A]
 *                [--mount-roll-deg A] [FILE] */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "auv/auv_dvl_t.h"
#include "drivers/dvl/pd0.h"

static void num(double v)
{
    if (isfinite(v))
        printf("%.9g", v);
    else
        printf("null");
}

static void nums(const char *key, const double *v, int n)
{
    printf(",\"%s\":[", key);
    for (int i = 0; i < n; i++) {
        if (i)
            printf(",");
        num(v[i]);
    }
    printf("]");
}

static void print_ensemble(const pd0_ensemble *e, const auv_dvl_t *d)
{
    const pd0_rtc *t = &e->rtc;
    printf("{\"ok\":true,\"ensemble\":%u,\"frame\":\"%s\",\"beams\":%d,\"cells\":%d,\"beam_angle_deg\":%g,"
           "\"convex\":%d,\"facing_up\":%d,\"tilts_used\":%d,\"three_beam\":%d,\"cell_size_m\":%g,"
           "\"bin1_distance_m\":%g,\"serial_number\":%u,",
           e->ensemble_number, pd0_frame_name(e->frame), e->n_beams, e->n_cells, e->beam_angle_deg, e->convex,
           e->facing_up, e->tilts_used, e->three_beam, e->cell_size_m, e->bin1_distance_m, e->serial_number);
    printf("\"rtc\":[%d,%d,%d,%d,%d,%d,%d],\"rtc_valid\":%d,\"rtc_y2k\":%d,", t->year, t->month, t->day, t->hour,
           t->minute, t->second, t->hundredths, t->valid, t->y2k);
    printf("\"heading_deg\":%g,\"pitch_deg\":%g,\"roll_deg\":%g,\"depth_m\":%g,\"temperature_c\":%g,"
           "\"salinity_ppt\":%g,\"sound_speed_mps\":%g,\"unknown_types\":%d",
           e->heading_deg, e->pitch_deg, e->roll_deg, e->depth_m, e->temperature_c, e->salinity_ppt,
           e->sound_speed_mps, e->unknown_types);
    printf(",\"has_velocity\":%d,\"has_bottom_track\":%d", e->has_velocity, e->has_bottom_track);
    nums("bt_range_m", e->bt_range_m, 4);
    nums("bt_velocity_mps", e->bt_velocity_mps, 4);
    printf(",\"velocity_mps\":[");
    for (int c = 0; c < e->n_cells; c++) {
        printf(c ? ",[" : "[");
        for (int b = 0; b < PD0_PROFILE_BEAMS; b++) {
            if (b)
                printf(",");
            num(e->velocity_mps[c][b]);
        }
        printf("]");
    }
    printf("]");
    printf(",\"dvl\":{\"mode\":%d", d->mode);
    nums("velocity_mps", d->velocity_mps, 3);
    printf(",\"velocity_sigma_mps\":%g,\"altitude_m\":%.9g", d->velocity_sigma_mps, d->altitude_m);
    double r[4] = {d->beam_range_m[0], d->beam_range_m[1], d->beam_range_m[2], d->beam_range_m[3]};
    nums("beam_range_m", r, 4);
    printf(",\"device_frame\":%d,\"ensemble\":%lld,\"device_utime\":%lld,\"error_velocity_mps\":%.9g}}\n",
           d->device_frame, (long long)d->ensemble, (long long)d->device_utime, d->error_velocity_mps);
}

int main(int argc, char **argv)
{
    size_t chunk = 4096;
    pd0_mounting m;
    pd0_mounting_default(&m);
    const char *path = NULL;
    for (int i = 1; i < argc; i++) {
        double *angle = !strcmp(argv[i], "--mount-yaw-deg")     ? &m.yaw_rad
                        : !strcmp(argv[i], "--mount-pitch-deg") ? &m.pitch_rad
                        : !strcmp(argv[i], "--mount-roll-deg")  ? &m.roll_rad
                                                                : NULL;
        if (angle && i + 1 < argc) {
            *angle = atof(argv[++i]) * M_PI / 180.0;
        } else if (!strcmp(argv[i], "--chunk") && i + 1 < argc) {
            chunk = (size_t)atol(argv[++i]);
            if (chunk < 1 || chunk > 65536)
                chunk = 4096;
        } else if (!strcmp(argv[i], "--help") || argv[i][0] == '-' || path) {
            fprintf(stderr,
                    "usage: auv-pd0-dump [--chunk N] [--mount-yaw-deg A] [--mount-pitch-deg A] "
                    "[--mount-roll-deg A] [FILE]\n");
            return strcmp(argv[i], "--help") ? 2 : 0;
        } else {
            path = argv[i];
        }
    }
    FILE *f = path ? fopen(path, "rb") : stdin;
    if (!f) {
        perror(path);
        return 1;
    }
    static pd0_framer fr;
    static pd0_ensemble e;
    static uint8_t buf[65536];
    pd0_framer_init(&fr);
    pd0_continuity cont = {0};
    unsigned long refused[PD0_RESULT_COUNT] = {0}, ok = 0;
    size_t n;
    while ((n = fread(buf, 1, chunk, f)) > 0) {
        const uint8_t *p = buf, *ens;
        size_t used, len;
        int r;
        while ((r = pd0_framer_push(&fr, p, n, &used, &ens, &len)) != -1) {
            p += used;
            n -= used;
            if (r == PD0_OK)
                r = pd0_decode(ens, len, &e);
            if (r != PD0_OK) {
                refused[r]++;
                printf("{\"ok\":false,\"reason\":\"%s\"}\n", pd0_result_name((pd0_result)r));
                continue;
            }
            ok++;
            auv_dvl_t d;
            memset(&d, 0, sizeof d);
            pd0_to_dvl(&e, &m, &d);
            pd0_continuity_update(&cont, e.ensemble_number, pd0_rtc_utime(&e.rtc));
            print_ensemble(&e, &d);
        }
    }
    if (path)
        fclose(f);
    if (pd0_framer_flush(&fr) == PD0_TRUNCATED) {
        refused[PD0_TRUNCATED]++;
        printf("{\"ok\":false,\"reason\":\"%s\"}\n", pd0_result_name(PD0_TRUNCATED));
    }
    printf("{\"summary\":true,\"ensembles\":%lu,\"garbage_bytes\":%llu,\"waves_packets\":%llu,\"gaps\":%llu,"
           "\"missed\":%llu,\"repeats\":%llu,\"restarts\":%llu,\"refused\":{",
           ok, (unsigned long long)fr.garbage_bytes, (unsigned long long)fr.waves_packets, (unsigned long long)cont.gaps,
           (unsigned long long)cont.missed, (unsigned long long)cont.repeats, (unsigned long long)cont.restarts);
    int first = 1;
    for (int r = 1; r < PD0_RESULT_COUNT; r++)
        if (refused[r]) {
            printf("%s\"%s\":%lu", first ? "" : ",", pd0_result_name((pd0_result)r), refused[r]);
            first = 0;
        }
    printf("}}\n");
    return 0;
}
