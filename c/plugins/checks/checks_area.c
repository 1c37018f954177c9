/* outside_area: true when the vehicle is outside an operating area (or
 * within `margin` of its edge), given as a polygon string or a box.
 *
 *   outside_area(polygon = "0,0; 0,500; 300,500; 300,0")
 *   outside_area(north = 0 m, east = 0 m, length = 300 m, width = 500 m, heading = 0 deg)
 *
 * The box has a corner at (north, east); `length` runs along `heading`
 * (0: north) and `width` to its right (heading 0: east).
 *
 * A malformed area cannot be refused by the loader (a test handler has no
 * hook that runs at load, and the loader checks only each value's type,
 * unit and range), so it fails safe: the test is TRUE every cycle, which
 * sends the plan to its abort state at once, and the reason goes to the
 * manager's log once. Likewise an unknown position (not a number) counts as
 * outside.
 *
 * Parsing a polygon costs O(n^2) (the self-intersection check), so parsed
 * areas are cached by the address of the plan's string and checked against
 * a copy of its text. The cache is per process and not thread-safe: one
 * manager steps one machine in one thread. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "plugins/checks/checks.h"
#include "plugins/lib/pu_polygon.h"

#define TEXT_MAX_CHARS 4095           /* longest polygon text */
#define TEXT_MAX (TEXT_MAX_CHARS + 1)
#define STR_(x) #x
#define STR(x) STR_(x)

const chasm_param_spec checks_outside_area_params[AREA_NPARAMS] = {
    /* The limits are in the description so that planners read them from
     * `chasm describe checks` (python/tools/plan/plugin_limits.py), not a copy. */
    [AREA_POLYGON] = CHASM_PARAM_STRING("polygon", "",
                                        "vertices \"north,east; ...\" in metres (or give a box); at most "
                                        STR(PU_POLYGON_MAX) " vertices and " STR(TEXT_MAX_CHARS) " characters"),
    [AREA_NORTH] = CHASM_PARAM_DOUBLE_RANGE("north", "m", 0, -1e7, 1e7, "box corner, north"),
    [AREA_EAST] = CHASM_PARAM_DOUBLE_RANGE("east", "m", 0, -1e7, 1e7, "box corner, east"),
    [AREA_LENGTH] = CHASM_PARAM_DOUBLE_RANGE("length", "m", 0, 0, 1e7, "box side along heading"),
    [AREA_WIDTH] = CHASM_PARAM_DOUBLE_RANGE("width", "m", 0, 0, 1e7, "box side to the right of heading"),
    [AREA_HEADING] = CHASM_PARAM_DOUBLE_RANGE("heading", "rad", 0, -6.283185307179586, 6.283185307179586,
                                              "direction of the box's length (0: north)"),
    [AREA_MARGIN] = CHASM_PARAM_DOUBLE_RANGE("margin", "m", 0, 0, 1e6, "also true this close to the edge, inside"),
    [AREA_AT_NORTH] = CHASM_READ("at_north", CHASM_DOUBLE, "m", "nav.north_m", "vehicle position, north"),
    [AREA_AT_EAST] = CHASM_READ("at_east", CHASM_DOUBLE, "m", "nav.east_m", "vehicle position, east"),
};

#define CACHE_SLOTS 16

typedef struct {
    const char *key;          /* the plan's string (stable for the machine's life) */
    char text[TEXT_MAX];      /* its text when parsed: a new machine may reuse the address */
    pu_polygon poly;
    char error[200];          /* "" if the polygon is good */
    int reported;
} cached_area;

static cached_area cache[CACHE_SLOTS];
static unsigned next_slot;

static cached_area *lookup(const char *text)
{
    /* texts longer than the copy compare on their first TEXT_MAX - 1 characters */
    for (int i = 0; i < CACHE_SLOTS; i++)
        if (cache[i].key == text && !strncmp(cache[i].text, text, TEXT_MAX - 1))
            return &cache[i];
    cached_area *a = &cache[next_slot++ % CACHE_SLOTS];
    a->key = text;
    a->reported = 0;
    a->error[0] = '\0';
    snprintf(a->text, sizeof a->text, "%s", text);
    char err[160];
    if (strlen(text) >= TEXT_MAX)
        snprintf(a->error, sizeof a->error, "the polygon text is longer than %d characters", TEXT_MAX - 1);
    else if (pu_polygon_parse(text, &a->poly, err, sizeof err) != 0)
        snprintf(a->error, sizeof a->error, "%s", err);
    return a;
}

/* Fail safe: report once, and count as outside. */
static int fail(chasm_ctx *c, int *reported, const char *why)
{
    if (!*reported) {
        char msg[320];
        snprintf(msg, sizeof msg, "outside_area: %s: the test is true until the plan is fixed", why);
        chasm_log(c, msg);
        *reported = 1;
    }
    return 1;
}

static int box_reported; /* a bad box has no string to key on: one message per process */

int checks_outside_area_evaluate(chasm_ctx *c)
{
    const char *text = chasm_param_string(c, AREA_POLYGON);
    double length = chasm_param_double(c, AREA_LENGTH), width = chasm_param_double(c, AREA_WIDTH);
    int has_polygon = text && text[0], has_box = length > 0.0 || width > 0.0;
    pu_polygon box;
    const pu_polygon *area = &box;
    if (has_polygon && has_box)
        return fail(c, &box_reported, "give either polygon or a box (length, width), not both");
    if (has_polygon) {
        cached_area *a = lookup(text);
        if (a->error[0])
            return fail(c, &a->reported, a->error);
        area = &a->poly;
    } else {
        if (!(length > 0.0 && width > 0.0))
            return fail(c, &box_reported, "no area: give polygon = \"n,e; n,e; ...\", or a box with length > 0 "
                                           "and width > 0");
        double h = chasm_param_double(c, AREA_HEADING);
        double n0 = chasm_param_double(c, AREA_NORTH), e0 = chasm_param_double(c, AREA_EAST);
        pu_polygon_box(&box, 0.0, 0.0, length, width);
        for (int i = 0; i < box.n; i++) { /* rotate about the corner, then place it */
            double n = box.north[i], e = box.east[i];
            box.north[i] = n0 + n * cos(h) - e * sin(h);
            box.east[i] = e0 + n * sin(h) + e * cos(h);
        }
    }
    double n = chasm_read_double(c, AREA_AT_NORTH), e = chasm_read_double(c, AREA_AT_EAST);
    if (!isfinite(n) || !isfinite(e))
        return 1;
    if (!pu_polygon_contains(area, n, e))
        return 1;
    double margin = chasm_param_double(c, AREA_MARGIN);
    return margin > 0.0 && pu_polygon_edge_distance(area, n, e) < margin;
}
