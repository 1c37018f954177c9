/* Opening one plugin file safely (see cm_plugin_file.h): read, structural
 * check, private copy, probe in a child, dlopen, descriptor check. Also the
 * plugin-name rule and the public open/close of a plugin on its own. */
#include "chasm/cm_plugin_file.h"

#include <dlfcn.h>
#include <errno.h>
#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "chasm/chasm.h"
#include "chasm/cm_elf_check.h"
#include "chasm/cm_units.h"

int mkstemps(char *, int);

int cm_plugin_probe_ms = CM_PLUGIN_PROBE_MS;

int chasm_plugin_name_check(const char *name, char *err, size_t el)
{
    size_t n = name ? strlen(name) : 0;
    const char *why = NULL;
    if (!n) why = "it is empty";
    else if (n > CHASM_PLUGIN_NAME_MAX) why = "it is longer than " CHASM_PLUGIN_NAME_MAX_TEXT " characters";
    else if (!(name[0] >= 'a' && name[0] <= 'z')) why = "it must begin with a lower-case letter";
    else
        for (size_t i = 0; i < n && !why; i++)
            if (!(name[i] == '_' || (name[i] >= 'a' && name[i] <= 'z') || (name[i] >= '0' && name[i] <= '9')))
                why = "only a-z, 0-9 and _ may follow (no dots, slashes or spaces)";
    if (!why) return 0;
    /* the name may hold anything: show it escaped and cut */
    char shown[80];
    size_t k = 0, i = 0;
    for (; i < n && k + 5 < sizeof shown; i++) {
        unsigned char c = (unsigned char)name[i];
        k += (size_t)snprintf(shown + k, sizeof shown - k, c >= 32 && c < 127 && c != '\'' ? "%c" : "\\x%02x", c);
    }
    shown[k] = 0;
    snprintf(err, el, "'%s%s' is not a plugin name: %s", shown, i < n ? "..." : "", why);
    return -1;
}

/* ------------------------------------------------------------ descriptor */

static int valid_spec_list(const chasm_param_spec *p, size_t n, int is_test, char *err, size_t el, const char *what)
{
    if (n > 64 || (n && !p)) {
        snprintf(err, el, "%s: bad parameter table (%zu entries)", what, n);
        return -1;
    }
    for (size_t i = 0; i < n; i++) {
        if (!p[i].name) {
            /* a table indexed by a slot enum ([SLOT] = ...) with a slot left out */
            snprintf(err, el, "%s: parameter slot %zu of %zu is empty (a hole in its table: no entry for that slot)",
                     what, i, n);
            return -1;
        }
        if (!p[i].name[0]) {
            snprintf(err, el, "%s: parameter %zu has no name", what, i);
            return -1;
        }
        if (p[i].flags & ~CHASM_SPEC_NO_DEFAULT) {
            snprintf(err, el, "%s: parameter '%s' has flags 0x%x this CHASM does not know", what, p[i].name,
                     p[i].flags);
            return -1;
        }
        if ((p[i].flags & CHASM_SPEC_NO_DEFAULT) && (p[i].kind != CHASM_PARAM || p[i].required)) {
            snprintf(err, el, "%s: parameter '%s' is marked optional without a default, which only an optional "
                     "CHASM_PARAM can be", what, p[i].name);
            return -1;
        }
        if ((unsigned)p[i].type > CHASM_MESSAGES || (unsigned)p[i].kind > CHASM_WRITES) {
            snprintf(err, el, "%s: parameter '%s' has an unknown type or kind", what, p[i].name);
            return -1;
        }
        if (p[i].type == CHASM_MESSAGES && p[i].kind == CHASM_PARAM) {
            snprintf(err, el, "%s: parameter '%s' is of type messages but not a variable (messages slots are "
                     "CHASM_READS or CHASM_WRITES)", what, p[i].name);
            return -1;
        }
        if (p[i].type == CHASM_MESSAGES && is_test) {
            /* a test evaluates and must not consume: taking messages is a behavior's job */
            snprintf(err, el, "%s: test handlers may not take messages ('%s'): read them in a behavior", what, p[i].name);
            return -1;
        }
        if (is_test && p[i].kind == CHASM_WRITES) {
            snprintf(err, el, "%s: test handlers may not write variables ('%s')", what, p[i].name);
            return -1;
        }
        const cm_unit *u = cm_unit_find(p[i].unit ? p[i].unit : "");
        if (!u || (u->dim != CM_DIM_NONE && p[i].type != CHASM_DOUBLE)) {
            snprintf(err, el, "%s: parameter '%s' has an unknown or misplaced unit '%s'", what, p[i].name,
                     p[i].unit ? p[i].unit : "");
            return -1;
        }
        for (size_t j = 0; j < i; j++)
            if (!strcmp(p[j].name, p[i].name)) {
                snprintf(err, el, "%s: parameter '%s' is listed twice", what, p[i].name);
                return -1;
            }
    }
    return 0;
}

static int valid_descriptor(const chasm_plugin_descriptor *d, const char *path, char *err, size_t el)
{
    if (d->abi_version != CHASM_PLUGIN_ABI || d->struct_size != sizeof *d) {
        snprintf(err, el, "'%s' was built for plugin ABI %u, this CHASM uses ABI %d: rebuild it against chasm_plugin.h",
                 path, d->abi_version, CHASM_PLUGIN_ABI);
        return -1;
    }
    if (!d->name || !d->name[0] || !d->version || d->n_behaviors > 1024 || d->n_tests > 1024 ||
        (d->n_behaviors && !d->behaviors) || (d->n_tests && !d->tests)) {
        snprintf(err, el, "'%s' has an invalid descriptor (name, version or tables missing)", path);
        return -1;
    }
    char why[256];
    if (chasm_plugin_name_check(d->name, why, sizeof why)) {
        snprintf(err, el, "'%s' calls itself %s", path, why);
        return -1;
    }
    char what[256];
    for (size_t i = 0; i < d->n_behaviors; i++) {
        const chasm_behavior_spec *b = &d->behaviors[i];
        if (!b->name || !b->step) {
            snprintf(err, el, "plugin '%s': behavior %zu has no name or no step function", d->name, i);
            return -1;
        }
        snprintf(what, sizeof what, "plugin '%s': behavior '%s'", d->name, b->name);
        if (valid_spec_list(b->params, b->n_params, 0, err, el, what)) return -1;
    }
    for (size_t i = 0; i < d->n_tests; i++) {
        const chasm_test_spec *t = &d->tests[i];
        if (!t->name || !t->evaluate) {
            snprintf(err, el, "plugin '%s': test handler %zu has no name or no evaluate function", d->name, i);
            return -1;
        }
        snprintf(what, sizeof what, "plugin '%s': test handler '%s'", d->name, t->name);
        if (valid_spec_list(t->params, t->n_params, 1, err, el, what)) return -1;
    }
    return 0;
}

/* dlopen + dlsym + descriptor check; the same steps in the probe and for real. */
static void *open_copy(const char *copy, const char *path, const chasm_plugin_descriptor **out, char *err, size_t el)
{
    dlerror();
    void *dl = dlopen(copy, RTLD_NOW | RTLD_LOCAL);
    if (!dl) {
        const char *e = dlerror();
        const char *colon = e ? strstr(e, ".so: ") : NULL;
        snprintf(err, el, "cannot load plugin file '%s': %s", path, colon ? colon + 5 : e ? e : "dlopen failed");
        return NULL;
    }
    const chasm_plugin_descriptor *d = dlsym(dl, CHASM_PLUGIN_SYMBOL);
    if (!d) {
        snprintf(err, el, "'%s' does not export the symbol '%s' (is it a CHASM plugin? see chasm_plugin.h)", path,
                 CHASM_PLUGIN_SYMBOL);
        dlclose(dl);
        return NULL;
    }
    if (valid_descriptor(d, path, err, el)) {
        dlclose(dl);
        return NULL;
    }
    *out = d;
    return dl;
}

/* ------------------------------------------------------------ read, copy */

static unsigned char *read_whole(const char *path, size_t *n, char *err, size_t el)
{
    /* O_NONBLOCK: a FIFO named like a plugin must not block the loader */
    int fd = open(path, O_RDONLY | O_NONBLOCK | O_CLOEXEC | O_NOCTTY);
    if (fd < 0) {
        snprintf(err, el, "cannot read plugin file '%s': %s", path, strerror(errno));
        return NULL;
    }
    struct stat st;
    const char *why = NULL;
    if (fstat(fd, &st)) why = strerror(errno);
    else if (S_ISDIR(st.st_mode)) why = "it is a directory";
    else if (!S_ISREG(st.st_mode)) why = "it is not a regular file";
    else if (st.st_size == 0) why = "it is empty (0 bytes)";
    else if ((unsigned long long)st.st_size > CM_PLUGIN_MAX_BYTES) why = "it is larger than the 64 MiB a plugin may have";
    if (why) {
        snprintf(err, el, "cannot read plugin file '%s': %s", path, why);
        close(fd);
        return NULL;
    }
    size_t want = (size_t)st.st_size, got = 0;
    unsigned char *buf = malloc(want + 1); /* +1: a file that grew is noticed */
    if (!buf) abort();
    ssize_t r = 1;
    while (got <= want && (r = read(fd, buf + got, want + 1 - got)) > 0) got += (size_t)r;
    int e = errno;
    close(fd);
    if (r < 0 || got != want) {
        snprintf(err, el, "cannot read plugin file '%s': %s", path,
                 r < 0 ? strerror(e) : "it changed size while it was read");
        free(buf);
        return NULL;
    }
    *n = got;
    return buf;
}

static int write_copy(const unsigned char *data, size_t n, char *copy, size_t cl, char *err, size_t el)
{
    const char *t = getenv("TMPDIR");
    snprintf(copy, cl, "%s/chasm-plugins-XXXXXX.so", t && t[0] ? t : "/tmp");
    int fd = mkstemps(copy, 3);
    if (fd < 0) {
        snprintf(err, el, "cannot create a private copy of the plugin in '%s': %s", t && t[0] ? t : "/tmp", strerror(errno));
        return -1;
    }
    size_t done = 0;
    while (done < n) {
        ssize_t w = write(fd, data + done, n - done);
        if (w <= 0) break;
        done += (size_t)w;
    }
    int e = errno;
    if (close(fd) || done != n) {
        snprintf(err, el, "cannot write a private copy of the plugin to '%s': %s", copy, strerror(e ? e : EIO));
        unlink(copy);
        return -1;
    }
    return 0;
}

/* ------------------------------------------------------------ probe */

static long long ms_now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (long long)ts.tv_sec * 1000 + ts.tv_nsec / 1000000;
}

/* The child loads the copy, unloads it again (destructors run at unload
 * too) and reports "OK" or "NO<reason>" on the pipe. A fault must kill it by
 * its signal, not go to a handler the process installed (a sanitizer's would
 * print a report and exit), and what the plugin prints is not the loader's
 * output. */
static _Noreturn void probe_child(int wfd, const char *copy, const char *path)
{
    static const int fatal[] = {SIGSEGV, SIGBUS, SIGILL, SIGFPE, SIGABRT, SIGTRAP, SIGSYS};
    struct sigaction dfl;
    memset(&dfl, 0, sizeof dfl);
    dfl.sa_handler = SIG_DFL;
    for (size_t i = 0; i < sizeof fatal / sizeof fatal[0]; i++) sigaction(fatal[i], &dfl, NULL);
    int null = open("/dev/null", O_WRONLY | O_CLOEXEC);
    if (null >= 0) {
        dup2(null, STDOUT_FILENO);
        dup2(null, STDERR_FILENO);
    }
    char msg[1024];
    const chasm_plugin_descriptor *d = NULL;
    void *dl = open_copy(copy, path, &d, msg + 2, sizeof msg - 2);
    if (dl) dlclose(dl);
    memcpy(msg, dl ? "OK" : "NO", 2);
    size_t len = dl ? 2 : 2 + strlen(msg + 2);
    ssize_t w = write(wfd, msg, len);
    (void)w;
    _exit(0); /* no atexit handlers, no stdio flush of the parent's buffers */
}

static int probe(const char *copy, const char *path, char *err, size_t el)
{
    int fds[2];
    if (pipe(fds)) {
        snprintf(err, el, "cannot probe plugin file '%s': %s", path, strerror(errno));
        return -1;
    }
    pid_t pid = fork();
    if (pid < 0) {
        snprintf(err, el, "cannot probe plugin file '%s' (fork: %s): not loaded", path, strerror(errno));
        close(fds[0]);
        close(fds[1]);
        return -1;
    }
    if (pid == 0) {
        close(fds[0]);
        probe_child(fds[1], copy, path);
    }
    close(fds[1]);
    char msg[1100];
    size_t got = 0;
    int timed_out = 0;
    long long deadline = ms_now() + cm_plugin_probe_ms;
    for (;;) {
        long long left = deadline - ms_now();
        if (left <= 0) {
            timed_out = 1;
            break;
        }
        struct pollfd p = {.fd = fds[0], .events = POLLIN};
        int r = poll(&p, 1, (int)left);
        if (r < 0 && errno == EINTR) continue;
        if (r <= 0) continue; /* re-check the deadline */
        ssize_t n = read(fds[0], msg + got, sizeof msg - 1 - got);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) break; /* EOF: the child is gone */
        got += (size_t)n;
        if (got == sizeof msg - 1) break;
    }
    msg[got] = 0;
    close(fds[0]);
    if (timed_out) kill(pid, SIGKILL);
    int st = 0;
    while (waitpid(pid, &st, 0) < 0 && errno == EINTR) {}
    if (timed_out) {
        snprintf(err, el, "cannot load plugin file '%s': it did not finish loading within %d ms in the probe process "
                          "(a constructor that hangs?)", path, cm_plugin_probe_ms);
        return -1;
    }
    if (WIFSIGNALED(st)) {
        snprintf(err, el, "cannot load plugin file '%s': it crashed the probe process that loads it first "
                          "(signal %d, %s): not loaded", path, WTERMSIG(st), strsignal(WTERMSIG(st)));
        return -1;
    }
    if (got >= 2 && !memcmp(msg, "NO", 2)) {
        snprintf(err, el, "%s", msg + 2);
        return -1;
    }
    if (got != 2 || memcmp(msg, "OK", 2) || !WIFEXITED(st) || WEXITSTATUS(st) != 0) {
        snprintf(err, el, "cannot load plugin file '%s': it ended the probe process that loads it first (exit status %d) "
                          "before it was loaded (a constructor that exits?): not loaded", path,
                 WIFEXITED(st) ? WEXITSTATUS(st) : -1);
        return -1;
    }
    return 0;
}

/* ------------------------------------------------------------ open */

int cm_plugin_code_open(const char *path, cm_plugin_code *out, char *err, size_t el)
{
    out->dl = NULL;
    out->desc = NULL;
    out->check = NULL;
    size_t n = 0;
    unsigned char *data = read_whole(path, &n, err, el);
    if (!data) return -1;
    char why[512];
    if (cm_elf_check(data, n, why, sizeof why)) {
        snprintf(err, el, "cannot load plugin file '%s': %s", path, why);
        free(data);
        return -1;
    }
    char copy[4200];
    int rc = write_copy(data, n, copy, sizeof copy, err, el);
    free(data);
    if (rc) return -1;
    if (probe(copy, path, err, el)) {
        unlink(copy);
        return -1;
    }
    out->dl = open_copy(copy, path, &out->desc, err, el);
    unlink(copy); /* the mapping stays; nothing is left on disk */
    if (!out->dl) return -1;
    void *check = dlsym(out->dl, CHASM_PLUGIN_CHECK_SYMBOL);
    memcpy(&out->check, &check, sizeof check); /* ISO C has no object-to-function pointer cast */
    return 0;
}

void cm_plugin_code_close(cm_plugin_code *c)
{
    if (c->dl) dlclose(c->dl);
    c->dl = NULL;
    c->desc = NULL;
    c->check = NULL;
}

/* ------------------------------------------------------------ public */

struct chasm_plugin_file {
    cm_plugin_code code;
};

chasm_plugin_file *chasm_plugin_file_open(const char *path, const char *name, char *err, size_t el)
{
    char tmp[1024];
    if (!err) {
        err = tmp;
        el = sizeof tmp;
    }
    if (name && chasm_plugin_name_check(name, err, el)) return NULL;
    cm_plugin_code c;
    if (cm_plugin_code_open(path, &c, err, el)) return NULL;
    if (name && strcmp(c.desc->name, name)) {
        snprintf(err, el, "plugin file '%s' holds plugin '%s', not '%s'", path, c.desc->name, name);
        cm_plugin_code_close(&c);
        return NULL;
    }
    chasm_plugin_file *f = calloc(1, sizeof *f);
    if (!f) abort();
    f->code = c;
    return f;
}

const chasm_plugin_descriptor *chasm_plugin_file_descriptor(const chasm_plugin_file *f) { return f->code.desc; }

void chasm_plugin_file_close(chasm_plugin_file *f)
{
    if (!f) return;
    cm_plugin_code_close(&f->code);
    free(f);
}
