#include "common/auth_keys.h"

#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include <openssl/crypto.h>

static int id_char(char c)
{
    return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_' || c == '-' ||
           c == '.';
}

static int hex_val(char c)
{
    if (c >= '0' && c <= '9') return c - '0';
    if (c >= 'a' && c <= 'f') return c - 'a' + 10;
    if (c >= 'A' && c <= 'F') return c - 'A' + 10;
    return -1;
}

/* One "KEY_ID HEX" line into k; NULL, or what is wrong with it. */
static const char *parse_line(char *line, auth_key *k)
{
    char *id = strtok(line, " \t\r\n"), *hex = strtok(NULL, " \t\r\n");
    if (!id || !hex || strtok(NULL, " \t\r\n"))
        return "a key line is 'KEY_ID HEX_SECRET'";
    size_t n = strlen(id);
    if (n > AUTH_MAX_KEY_ID)
        return "key id longer than 32 characters";
    for (size_t i = 0; i < n; i++)
        if (!id_char(id[i]))
            return "key id of letters, digits, '_', '-' and '.' only";
    size_t h = strlen(hex);
    if (h % 2 || h / 2 < AUTH_MIN_SECRET || h / 2 > AUTH_MAX_SECRET)
        return "secret must be 16 to 64 bytes in hex (auv-keygen writes 32)";
    for (size_t i = 0; i < h / 2; i++) {
        int a = hex_val(hex[2 * i]), b = hex_val(hex[2 * i + 1]);
        if (a < 0 || b < 0)
            return "secret is not hex";
        k->secret[i] = (uint8_t)(a << 4 | b);
    }
    memcpy(k->id, id, n + 1);
    k->len = h / 2;
    return NULL;
}

static int fail(char *err, size_t el, const char *path, int line, const char *why)
{
    if (line > 0) snprintf(err, el, "%s:%d: %s", path, line, why);
    else snprintf(err, el, "%s: %s", path, why);
    return -1;
}

int auth_keys_load(const char *path, auth_keyring *ring, char *err, size_t el)
{
    memset(ring, 0, sizeof *ring);
    int fd = open(path, O_RDONLY | O_CLOEXEC | O_NOFOLLOW);
    if (fd < 0)
        return fail(err, el, path, 0, strerror(errno));
    struct stat st;
    char why[160];
    if (fstat(fd, &st) || !S_ISREG(st.st_mode)) {
        close(fd);
        return fail(err, el, path, 0, "not a regular file");
    }
    if (st.st_mode & 077) {
        close(fd);
        snprintf(why, sizeof why, "key file open to group or others (mode %04o): chmod 600 it",
                 (unsigned)(st.st_mode & 07777));
        return fail(err, el, path, 0, why);
    }
    FILE *f = fdopen(fd, "r");
    if (!f) {
        close(fd);
        return fail(err, el, path, 0, strerror(errno));
    }
    char line[512];
    int lineno = 0, rc = 0;
    while (rc == 0 && fgets(line, sizeof line, f)) {
        lineno++;
        char *p = line + strspn(line, " \t");
        if (*p == '#' || *p == '\n' || *p == '\r' || !*p)
            continue;
        const char *bad = ring->n >= AUTH_MAX_KEYS ? "more than 4 keys" : parse_line(p, &ring->keys[ring->n]);
        if (!bad && auth_keys_find(ring, ring->keys[ring->n].id))
            bad = "key id listed twice";
        if (bad)
            rc = fail(err, el, path, lineno, bad);
        else
            ring->n++;
    }
    OPENSSL_cleanse(line, sizeof line);
    fclose(f);
    if (rc == 0 && ring->n == 0)
        rc = fail(err, el, path, 0, "no key in it (write one with auv-keygen)");
    if (rc)
        auth_keys_clear(ring);
    return rc;
}

const auth_key *auth_keys_find(const auth_keyring *ring, const char *id)
{
    for (size_t i = 0; id && i < ring->n; i++)
        if (!strcmp(ring->keys[i].id, id))
            return &ring->keys[i];
    return NULL;
}

void auth_keys_clear(auth_keyring *ring)
{
    OPENSSL_cleanse(ring, sizeof *ring);
    ring->n = 0;
}
