#include "common/auth_verify.h"

#include <stdio.h>
#include <string.h>
#include <time.h>

static const char *const TEXT[AUTH_N_RESULTS] = {
    [AUTH_OK] = "ok",
    [AUTH_UNSIGNED] = "unsigned command (this receiver requires authenticated commands)",
    [AUTH_UNKNOWN_KEY] = "unknown key id",
    [AUTH_BAD_MAC] = "bad MAC",
    [AUTH_REPLAY] = "replay (counter not above the newest from its sender)",
    [AUTH_STALE] = "stale (counter more than 5 min from this host's clock)",
};

static const char *const NAME[AUTH_N_RESULTS] = {
    [AUTH_OK] = "ok", [AUTH_UNSIGNED] = "unsigned", [AUTH_UNKNOWN_KEY] = "unknown_key",
    [AUTH_BAD_MAC] = "bad_mac", [AUTH_REPLAY] = "replay", [AUTH_STALE] = "stale",
};

const char *auth_result_name(auth_result r) { return r >= 0 && r < AUTH_N_RESULTS ? NAME[r] : "?"; }
const char *auth_result_text(auth_result r) { return r >= 0 && r < AUTH_N_RESULTS ? TEXT[r] : "?"; }

int64_t auth_now_us(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_REALTIME, &ts);
    return (int64_t)ts.tv_sec * 1000000 + ts.tv_nsec / 1000;
}

static auth_peer *find_peer(auth_verifier *v, const char *key_id, const char *sender)
{
    for (size_t i = 0; i < v->n_peers; i++)
        if (!strcmp(v->peers[i].key_id, key_id) && !strncmp(v->peers[i].sender, sender, AUTH_MAX_SENDER))
            return &v->peers[i];
    return NULL;
}

/* A slot for a new sender: a free one, else the least recently heard. */
static auth_peer *new_peer(auth_verifier *v, const char *key_id, const char *sender)
{
    auth_peer *p = &v->peers[0];
    if (v->n_peers < AUTH_MAX_PEERS)
        p = &v->peers[v->n_peers++];
    else
        for (size_t i = 1; i < v->n_peers; i++)
            if (v->peers[i].heard < p->heard)
                p = &v->peers[i];
    memset(p, 0, sizeof *p);
    snprintf(p->key_id, sizeof p->key_id, "%s", key_id);
    snprintf(p->sender, sizeof p->sender, "%s", sender);
    p->counter = INT64_MIN;
    return p;
}

static auth_result check(auth_verifier *v, const auth_fields *a, const void *body, size_t len, int64_t now_us)
{
    if (!a->key_id || !*a->key_id || a->mac_len == 0)
        return AUTH_UNSIGNED;
    const auth_key *k = auth_keys_find(&v->ring, a->key_id);
    if (!k)
        return AUTH_UNKNOWN_KEY;
    uint8_t mac[AUTH_MAC_BYTES];
    if (a->mac_len != AUTH_MAC_BYTES || !a->mac || auth_hmac_sha256(k->secret, k->len, body, len, mac) ||
        !auth_mac_equal(mac, a->mac, AUTH_MAC_BYTES))
        return AUTH_BAD_MAC;
    /* Authentic from here on: the counter can be trusted to be the signer's. */
    int64_t d = a->counter - now_us;
    if (d > AUTH_STALE_US || d < -AUTH_STALE_US)
        return AUTH_STALE;
    const char *sender = a->sender ? a->sender : "";
    auth_peer *p = find_peer(v, a->key_id, sender);
    if (p && a->counter <= p->counter)
        return AUTH_REPLAY;
    if (!p)
        p = new_peer(v, a->key_id, sender);
    p->counter = a->counter;
    p->heard = ++v->tick;
    return AUTH_OK;
}

auth_result auth_verify(auth_verifier *v, const auth_fields *a, const void *body, size_t len, int64_t now_us)
{
    auth_result r = check(v, a, body, len, now_us);
    v->refused[r]++;
    return r;
}
