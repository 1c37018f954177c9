/* Survey areas and their track lines, for the lawnmower behavior.
 *
 * An area is a polygon (plugins/lib/pu_polygon.h: text "n,e; n,e; ...", metres
 * in the local NED frame) or a box: corner, length along the line heading, width to the
 * right of it (starboard looking along the heading). Lines run parallel to
 * the heading. The area's extent across the lines is cut into the fewest
 * equal strips no wider than the spacing, and one line runs down the middle
 * of each strip, from where it enters the area to where it leaves it (for a
 * concave polygon: from the first entry to the last exit). Lines alternate
 * direction, the first one along the heading on the left (port) side. */
#ifndef GD_SURVEY_H
#define GD_SURVEY_H

#include <stddef.h>

#include "plugins/lib/gd_geometry.h"
#include "plugins/lib/pu_polygon.h"

#define GD_MAX_LINES 500

/* A box as a polygon: corner c, `length` along `heading`, `width` to its right. */
PU_HIDDEN void gd_box_polygon(pu_polygon *out, gd_point c, double heading, double length, double width);

/* One track line: flown from start to end (the part inside the area). */
typedef struct {
    gd_point start, end;
} gd_track;

/* Fills lines (at most max) and returns their number, or -1 with a message in
 * err (more lines than max). spacing > 0. */
PU_HIDDEN int gd_survey_lines(const pu_polygon *area, double heading, double spacing, gd_track *lines, int max, char *err,
                    size_t errlen);

#endif
