/* A search vehicle's own contact list: repeated sidescan looks at one object
 * (within `merge` metres of a contact's estimate) become one contact whose
 * position is the inverse-variance mean of its looks and whose score is the
 * mean mine-likeness of its looks (one look that happens to score high is
 * less convincing than several that agree). Pure data, no engine. */
#ifndef TM_CONTACTS_H
#define TM_CONTACTS_H

#include "plugins/lib/pu_visibility.h"

#define TM_MAX_CONTACTS 256

typedef struct {
    int number;           /* own contact number = index in the list */
    double n, e, sigma;   /* merged position estimate [m] and its 1-sigma */
    double score;         /* mean mine-likeness of the looks, [0, 1] */
    int looks;
    double t_first, t_last; /* mission time of the first and last look [s] */
    int queued;           /* 1 once reported as mine-like (stays so) */
} tm_contact;

typedef struct {
    tm_contact c[TM_MAX_CONTACTS];
    int n;
    long full;            /* looks dropped because the list was full */
} tm_contact_list;

/* Adds one look. Returns the index of the contact it created or merged into
 * (*created = 1 if new), or -1 when the list is full (counted). A sigma below
 * 0.1 m counts as 0.1 m (a perfect look must not freeze the estimate). */
PU_HIDDEN int tm_contacts_add(tm_contact_list *l, double n, double e, double sigma, double score, double t,
                              double merge_m, int *created);

#endif
