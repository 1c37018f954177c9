#include "chasm/cm_units.h"

#include <string.h>

#define PI 3.14159265358979323846

static const cm_unit units[] = {
    {"", CM_DIM_NONE, 1.0},
    {"m", CM_DIM_LENGTH, 1.0}, {"km", CM_DIM_LENGTH, 1000.0}, {"cm", CM_DIM_LENGTH, 0.01},
    {"mm", CM_DIM_LENGTH, 0.001}, {"nmi", CM_DIM_LENGTH, 1852.0}, {"ft", CM_DIM_LENGTH, 0.3048},
    {"s", CM_DIM_TIME, 1.0}, {"ms", CM_DIM_TIME, 0.001}, {"min", CM_DIM_TIME, 60.0},
    {"h", CM_DIM_TIME, 3600.0},
    {"rad", CM_DIM_ANGLE, 1.0}, {"deg", CM_DIM_ANGLE, PI / 180.0},
    {"m/s", CM_DIM_SPEED, 1.0}, {"kn", CM_DIM_SPEED, 1852.0 / 3600.0},
    {"knots", CM_DIM_SPEED, 1852.0 / 3600.0}, {"km/h", CM_DIM_SPEED, 1.0 / 3.6},
    {"cm/s", CM_DIM_SPEED, 0.01},
    {"rad/s", CM_DIM_ANGULAR_RATE, 1.0}, {"deg/s", CM_DIM_ANGULAR_RATE, PI / 180.0},
    {"rpm", CM_DIM_ANGULAR_RATE, 2.0 * PI / 60.0},
    {"Hz", CM_DIM_FREQUENCY, 1.0},
    {"V", CM_DIM_VOLTAGE, 1.0},
};

const cm_unit *cm_unit_find(const char *name)
{
    for (size_t i = 0; i < sizeof units / sizeof units[0]; i++)
        if (!strcmp(units[i].name, name)) return &units[i];
    return NULL;
}

const char *cm_unit_name_at(int i)
{
    return i >= 1 && (size_t)i < sizeof units / sizeof units[0] ? units[i].name : NULL;
}

const char *cm_dim_name(cm_dim d)
{
    static const char *n[] = {"a plain number", "a length", "a duration", "an angle",
                              "a speed", "an angular rate", "a frequency", "a voltage"};
    return n[d];
}

const char *cm_dim_si(cm_dim d)
{
    static const char *n[] = {"", "m", "s", "rad", "m/s", "rad/s", "Hz", "V"};
    return n[d];
}
