/* Plugin uploads: refuse what is not allowed, check what is, and keep only a
 * plugin that loaded and passed (see mgr_upload.h). */
#include "managers/mgr_upload.h"

#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <unistd.h>

#include "auv/auv_mission_ack_t.h"
#include "common/auth_mac.h"

#define REJECTED AUV_MISSION_ACK_T_RESULT_REJECTED
#define FAILED AUV_MISSION_ACK_T_RESULT_FAILED
#define OK AUV_MISSION_ACK_T_RESULT_OK
#define TEMP_PREFIX ".chasm_"
#define TEMP_MARK ".upload-"

/* The allowlist: lines "DIGEST NAME", '#' comments and blank lines ignored.
 * A digest allows exactly the plugin named on its line. 0 when allowed, else
 * -1 with the refusal in why. */
static int allowlisted(const char *allowlist, const char *hex, const char *name, char *why, size_t wl)
{
    FILE *f = fopen(allowlist, "r");
    if (!f) {
        snprintf(why, wl, "plugin rejected: cannot read the allowlist '%s': %s", allowlist, strerror(errno));
        return -1;
    }
    char *line = NULL;
    size_t cap = 0;
    int lineno = 0, found = 0;
    char other[80] = "";
    int nameless = 0;
    while (!found && getline(&line, &cap, f) >= 0) {
        lineno++;
        char digest[80] = "", who[80] = "";
        int n = sscanf(line, "%79s %79s", digest, who);
        if (n < 1 || digest[0] == '#' || strcasecmp(digest, hex)) continue;
        if (n < 2 || who[0] == '#') nameless = lineno;
        else if (!strcmp(who, name)) found = 1;
        else if (!other[0]) snprintf(other, sizeof other, "%s", who);
    }
    free(line);
    fclose(f);
    if (found) return 0;
    if (other[0])
        snprintf(why, wl, "plugin rejected: its digest is in the allowlist for plugin '%s', not for '%s'", other, name);
    else if (nameless)
        snprintf(why, wl, "plugin rejected: allowlist line %d lists its digest without a plugin name "
                          "(a line is 'DIGEST NAME')", nameless);
    else snprintf(why, wl, "plugin rejected: digest not in the allowlist");
    return -1;
}

/* Writes data to a new hidden file in dir; 0 and its path in tmp, or -1. */
static int write_temp(const char *dir, const char *name, const uint8_t *data, size_t n, char *tmp, size_t tl)
{
    snprintf(tmp, tl, "%s/" TEMP_PREFIX "%s.so" TEMP_MARK "XXXXXX", dir, name);
    int fd = mkstemp(tmp);
    if (fd < 0) return -1;
    size_t done = 0;
    while (done < n) {
        ssize_t w = write(fd, data + done, n - done);
        if (w <= 0) break;
        done += (size_t)w;
    }
    int ok = done == n && fsync(fd) == 0;
    int e = errno;
    if (close(fd)) ok = 0;
    if (!ok) {
        unlink(tmp);
        errno = e ? e : EIO;
        return -1;
    }
    return 0;
}

/* The new name is durable only once the directory is synced too. */
static void sync_dir(const char *dir)
{
    int fd = open(dir, O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (fd < 0) return;
    (void)fsync(fd);
    close(fd);
}

/* Errors name the hidden temporary file: say the file it would have become. */
static void name_the_upload(char *err, size_t el, const char *tmp, const char *path)
{
    char out[1400];
    size_t k = 0, tlen = strlen(tmp);
    for (const char *p = err; *p && k + 1 < sizeof out;) {
        if (!strncmp(p, tmp, tlen)) {
            k += (size_t)snprintf(out + k, sizeof out - k, "upload %s", path);
            if (k >= sizeof out) k = sizeof out - 1;
            p += tlen;
        } else out[k++] = *p++;
    }
    out[k] = 0;
    snprintf(err, el, "%s", out);
}

int8_t mgr_upload_plugin(manager_t *mg, const auv_plugin_upload_t *u, char *text, size_t tl)
{
    const char *name = u->plugin_name ? u->plugin_name : "";
    /* the version is free text from the sender: shown cut and printable */
    char version[48];
    size_t vk = 0;
    for (const char *c = u->plugin_version ? u->plugin_version : ""; *c && vk + 4 < sizeof version; c++)
        version[vk++] = (unsigned char)*c < 0x20 || (unsigned char)*c >= 0x7f ? '?' : *c;
    if (u->plugin_version && strlen(u->plugin_version) > vk) version[vk++] = '~';
    version[vk] = 0;
    char why[512];
    if (u->vehicle && *u->vehicle && strcmp(u->vehicle, mg->opt.vehicle)) {
        snprintf(text, tl, "plugin rejected: the upload is for vehicle '%.64s', this is '%s'", u->vehicle, mg->opt.vehicle);
        return REJECTED;
    }
    if (!mg->opt.plugin_dir || !mg->opt.allowlist) {
        snprintf(text, tl, "plugin rejected: this manager takes no uploads (start it with --plugin-dir DIR --allowlist FILE)");
        return REJECTED;
    }
    if (chasm_plugin_name_check(name, why, sizeof why)) {
        snprintf(text, tl, "plugin rejected: bad plugin name: %s", why);
        return REJECTED;
    }
    if (u->n_bytes <= 0 || u->n_bytes > MGR_MAX_UPLOAD_BYTES) {
        snprintf(text, tl, "plugin rejected: %d bytes (a plugin has 1 to %d)", (int)u->n_bytes, MGR_MAX_UPLOAD_BYTES);
        return REJECTED;
    }
    char hex[65];
    auth_sha256_hex(u->data, (size_t)u->n_bytes, hex);
    if (!u->sha256_hex || strcasecmp(hex, u->sha256_hex)) {
        snprintf(text, tl, "plugin rejected: data does not match its SHA-256");
        return REJECTED;
    }
    if (allowlisted(mg->opt.allowlist, hex, name, text, tl)) return REJECTED;

    char tmp[1200], path[1100];
    snprintf(path, sizeof path, "%s/chasm_%s.so", mg->opt.plugin_dir, name);
    if (write_temp(mg->opt.plugin_dir, name, u->data, (size_t)u->n_bytes, tmp, sizeof tmp)) {
        snprintf(text, tl, "plugin %s %s not written to %s: %s; mission unchanged", name, version, mg->opt.plugin_dir,
                 strerror(errno));
        return FAILED;
    }
    /* Checked on its own first (and for the name it claims), so a plugin the
     * running plan does not use is kept only if it would load. */
    char err[1400];
    chasm_plugin_file *pf = chasm_plugin_file_open(tmp, name, err, sizeof err);
    int uses = chasm_uses_plugin(mg->plan.machine, name);
    if (pf) chasm_plugin_file_close(pf);
    if (!pf || (uses && chasm_hotplug(mg->plan.machine, tmp, err, sizeof err) != 0)) {
        unlink(tmp);
        name_the_upload(err, sizeof err, tmp, path);
        snprintf(text, tl, "plugin %s %s not loaded, mission unchanged: %s", name, version, err);
        return FAILED;
    }
    if (rename(tmp, path) != 0) {
        int e = errno;
        unlink(tmp);
        if (uses) {
            snprintf(text, tl, "plugin %s %s loaded, but not saved as %s (%s): the next start uses the old file", name,
                     version, path, strerror(e));
            return OK;
        }
        snprintf(text, tl, "plugin %s %s not saved as %s: %s", name, version, path, strerror(e));
        return FAILED;
    }
    sync_dir(mg->opt.plugin_dir);
    if (uses) snprintf(text, tl, "plugin %s %s loaded; used from the next entry of its states", name, version);
    else snprintf(text, tl, "plugin %s %s checked and saved as %s; the running plan does not use it", name, version, path);
    return OK;
}

void mgr_upload_clean_dir(const manager_t *mg)
{
    DIR *d = mg->opt.plugin_dir ? opendir(mg->opt.plugin_dir) : NULL;
    if (!d) return;
    struct dirent *e;
    while ((e = readdir(d)))
        if (!strncmp(e->d_name, TEMP_PREFIX, strlen(TEMP_PREFIX)) && strstr(e->d_name, TEMP_MARK)) {
            char p[1200];
            snprintf(p, sizeof p, "%s/%s", mg->opt.plugin_dir, e->d_name);
            if (unlink(p) == 0) fprintf(stderr, "%s: removed %s, left by an interrupted upload\n", mg->opt.name, p);
        }
    closedir(d);
}
