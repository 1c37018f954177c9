/* Units of the plan language. A number written with a unit is converted to
 * the unit its destination declares (a variable's declared unit, or a plugin
 * schema's SI unit); a unit of another dimension is a load error. */
#ifndef CM_UNITS_H
#define CM_UNITS_H

typedef enum {
    CM_DIM_NONE = 0, CM_DIM_LENGTH, CM_DIM_TIME, CM_DIM_ANGLE, CM_DIM_SPEED,
    CM_DIM_ANGULAR_RATE, CM_DIM_FREQUENCY, CM_DIM_VOLTAGE
} cm_dim;

typedef struct {
    const char *name;     /* "m/s" */
    cm_dim dim;
    double to_si;         /* value_si = value * to_si */
} cm_unit;

const cm_unit *cm_unit_find(const char *name);   /* NULL if unknown; "" -> the no-unit entry */
const char *cm_dim_name(cm_dim d);                /* "a length" */
const char *cm_dim_si(cm_dim d);                  /* "m" */
/* For did-you-mean: the i-th unit name, NULL past the end. */
const char *cm_unit_name_at(int i);
#endif
