#include "tm_contacts.h"

#include <math.h>

static double floor_sigma(double s) { return isfinite(s) && s > 0.1 ? s : 0.1; }

int tm_contacts_add(tm_contact_list *l, double n, double e, double sigma, double score, double t, double merge_m,
                    int *created)
{
    *created = 0;
    sigma = floor_sigma(sigma);
    int best = -1;
    double best_d = INFINITY;
    for (int i = 0; i < l->n; i++) {
        double d = hypot(l->c[i].n - n, l->c[i].e - e);
        if (d <= merge_m && d < best_d) {   /* nearest; ties keep the older contact */
            best = i;
            best_d = d;
        }
    }
    if (best >= 0) {
        tm_contact *k = &l->c[best];
        double wa = 1.0 / (k->sigma * k->sigma), wb = 1.0 / (sigma * sigma);
        k->n = (k->n * wa + n * wb) / (wa + wb);
        k->e = (k->e * wa + e * wb) / (wa + wb);
        k->sigma = sqrt(1.0 / (wa + wb));
        k->score = (k->score * k->looks + score) / (k->looks + 1);
        k->looks++;
        k->t_last = t;
        return best;
    }
    if (l->n >= TM_MAX_CONTACTS) {
        l->full++;
        return -1;
    }
    tm_contact *k = &l->c[l->n];
    *k = (tm_contact){l->n, n, e, sigma, score, 1, t, t, 0};
    *created = 1;
    return l->n++;
}
