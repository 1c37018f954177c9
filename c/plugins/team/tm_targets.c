#include "tm_targets.h"

#include <math.h>

static int same(tm_key a, tm_key b) { return a.origin == b.origin && a.number == b.number; }

static int find_key(const tm_target_queue *q, tm_key k)
{
    for (int i = 0; i < q->n; i++) {
        if (same(q->t[i].key, k))
            return i;
        for (int j = 0; j < q->t[i].n_alias; j++)
            if (same(q->t[i].alias[j], k))
                return i;
    }
    return -1;
}

static void merge_position(tm_target *t, double n, double e, double sigma)
{
    double wa = 1.0 / (t->sigma * t->sigma), wb = 1.0 / (sigma * sigma);
    t->n = (t->n * wa + n * wb) / (wa + wb);
    t->e = (t->e * wa + e * wb) / (wa + wb);
    t->sigma = sqrt(1.0 / (wa + wb));
}

int tm_targets_report(tm_target_queue *q, tm_key k, double n, double e, double sigma, double score, double t,
                      double merge_m, int *created)
{
    *created = 0;
    if (!(isfinite(sigma) && sigma > 0.1))
        sigma = 0.1;
    int i = find_key(q, k);
    if (i >= 0) {
        /* a repeat of a report already merged: the reporter's estimate may
         * have improved, but counting it again would overweight one vehicle */
        if (score > q->t[i].score)
            q->t[i].score = score;
        return i;
    }
    int best = -1;
    double best_d = INFINITY;
    for (int j = 0; j < q->n; j++) {
        double d = hypot(q->t[j].n - n, q->t[j].e - e);
        if (d <= merge_m && d < best_d) {
            best = j;
            best_d = d;
        }
    }
    if (best >= 0) {
        tm_target *g = &q->t[best];
        if (g->n_alias < TM_MAX_ALIASES)
            g->alias[g->n_alias++] = k;
        merge_position(g, n, e, sigma);
        if (score > g->score)
            g->score = score;
        return best;
    }
    if (q->n >= TM_MAX_TARGETS) {
        q->full++;
        return -1;
    }
    tm_target *g = &q->t[q->n];
    *g = (tm_target){.key = k, .n = n, .e = e, .sigma = sigma, .score = score, .t_first = t};
    *created = 1;
    return q->n++;
}

void tm_target_where(const tm_target *t, double *n, double *e)
{
    *n = t->looks > 0 ? t->look_sum_n / t->looks : t->n;
    *e = t->looks > 0 ? t->look_sum_e / t->looks : t->e;
}

int tm_targets_look(tm_target_queue *q, double n, double e, int result, double confidence, double first_gate_m,
                    double gate_m, double max_error)
{
    if ((result != TM_RESULT_MINE && result != TM_RESULT_NOT_MINE) || !(confidence > 0.5) || !isfinite(n) ||
        !isfinite(e))
        return -1;
    int best = -1;
    double best_d = INFINITY;
    for (int j = 0; j < q->n; j++) {
        if (q->t[j].state != TM_T_PENDING)
            continue;
        double tn, te;
        tm_target_where(&q->t[j], &tn, &te);
        double d = hypot(tn - n, te - e);
        if (d <= (q->t[j].looks > 0 ? gate_m : first_gate_m) && d < best_d) {
            best = j;
            best_d = d;
        }
    }
    if (best < 0)
        return -1;
    tm_target *g = &q->t[best];
    double c = confidence < 1.0 - 1e-9 ? confidence : 1.0 - 1e-9;
    double w = log(c / (1.0 - c));
    g->llr += result == TM_RESULT_MINE ? w : -w;
    g->looks++;
    g->look_sum_n += n;
    g->look_sum_e += e;
    double a = max_error > 1e-12 ? (max_error < 0.5 ? max_error : 0.5) : 1e-12;
    /* a hair below the bound so that k equal looks decide when k * w equals
     * it on paper (log() rounding must not ask for one look more) */
    if (fabs(g->llr) < log((1.0 - a) / a) * (1.0 - 1e-12))
        return -2;
    g->state = TM_T_IDENTIFIED;
    g->result = g->llr > 0 ? TM_RESULT_MINE : TM_RESULT_NOT_MINE;
    g->look_n = n;
    g->look_e = e;
    return best;
}

int tm_targets_pending(const tm_target_queue *q, int *idx, int max)
{
    int k = 0;
    for (int j = 0; j < q->n && k < max; j++)
        if (q->t[j].state == TM_T_PENDING)
            idx[k++] = j;
    return k;
}
