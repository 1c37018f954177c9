/* libauvpilot.so's API (auv_pilot.h) over the plugin's loops (pilot_law.h). */
#include "pilotlib/auv_pilot.h"

#include <math.h>
#include <stddef.h>
#include <string.h>

#include "plugins/pilot/pilot_law.h"

/* The gains grouped as the behaviors take them, so each loop is handed the
 * struct its behavior would build from its parameters. */
typedef struct {
    pilot_heading_gains heading;
    pilot_depth_gains depth;
    pilot_prop_gains prop;
} gains;

struct auv_pilot {
    gains g;
    pilot_heading_loop heading;
    pilot_depth_loop vertical; /* its pitch loop is also pitch_control's */
    pilot_prop_loop prop;
};

static const struct {
    const char *name;
    size_t offset;
} table[] = {
#define AUV_PILOT_GAIN_ENTRY(param, field) {#param, offsetof(gains, field)},
    AUV_PILOT_GAINS(AUV_PILOT_GAIN_ENTRY)
#undef AUV_PILOT_GAIN_ENTRY
};
#define N_GAINS (sizeof table / sizeof table[0])

size_t auv_pilot_size(void) { return sizeof(auv_pilot); }

void auv_pilot_init(auv_pilot *p)
{
    memset(p, 0, sizeof *p);
    auv_pilot_start_heading(p, 0.0);
    auv_pilot_start_vertical(p, 0.0, 0.0);
    auv_pilot_start_prop(p, 0.0);
}

size_t auv_pilot_gain_count(void) { return N_GAINS; }

const char *auv_pilot_gain_name(size_t i) { return i < N_GAINS ? table[i].name : NULL; }

/* The byte offset of a gain in the gains struct, -1 for an unknown name. */
static long gain_offset(const char *name)
{
    for (size_t i = 0; i < N_GAINS; i++)
        if (strcmp(table[i].name, name) == 0)
            return (long)table[i].offset;
    return -1;
}

int auv_pilot_set_gain(auv_pilot *p, const char *name, double value)
{
    long off = gain_offset(name);
    if (off < 0)
        return -1;
    *(double *)((char *)&p->g + off) = value;
    return 0;
}

double auv_pilot_gain(const auv_pilot *p, const char *name)
{
    long off = gain_offset(name);
    return off < 0 ? NAN : *(const double *)((const char *)&p->g + off);
}

void auv_pilot_start_heading(auv_pilot *p, double rudder) { pilot_heading_start(&p->heading, rudder); }

void auv_pilot_start_vertical(auv_pilot *p, double pitch, double plane)
{
    pilot_depth_start(&p->vertical, pitch, plane);
}

void auv_pilot_start_prop(auv_pilot *p, double rpm) { pilot_prop_start(&p->prop, rpm); }

double auv_pilot_rudder(auv_pilot *p, double heading_cmd, double heading, double r, double dt)
{
    return pilot_heading_step(&p->heading, &p->g.heading, heading_cmd, heading, r, dt);
}

double auv_pilot_plane_for_depth(auv_pilot *p, double depth_cmd, double depth, double pitch, double q, double dt)
{
    return pilot_depth_step(&p->vertical, &p->g.depth, depth_cmd, depth, pitch, q, dt);
}

double auv_pilot_plane_for_pitch(auv_pilot *p, double pitch_cmd, double pitch, double q, double dt)
{
    /* the plan gives pitch_control max_pitch = $max_pitch, depth_control's too */
    return pilot_pitch_hold(&p->vertical.pitch, &p->g.depth.pitch, p->g.depth.max_pitch, pitch_cmd, pitch, q, dt);
}

double auv_pilot_prop_for_speed(auv_pilot *p, double speed_cmd, double u, int through_water, double dt)
{
    return pilot_speed_step(&p->prop, &p->g.prop, speed_cmd, u, through_water, dt);
}

double auv_pilot_prop_for_rpm(auv_pilot *p, double rpm_cmd, double dt)
{
    return pilot_rpm_step(&p->prop, &p->g.prop, rpm_cmd, dt);
}
