/* Plugins: a good one, and hot plug of new, broken and incompatible versions. */
#include <stdlib.h>
#include <unistd.h>

#include "chasm/cm_elf_check.h"
#include "../../harness/plan_test.h"

static const char *PLAN =
    "use test_basic\n"
    "input x : double m\ninput go : bool\noutput test.out : double m\n"
    "test go_on : go == true\ntest go_off : go == false\n"
    "state a {\n do hold(value = 3 m)\n test high : above(x = x, limit = 5 m)\n when high -> c\n when go_on -> b\n}\n"
    "state b {\n when go_off -> a\n}\n"
    "state c {\n}\n";

static void path_of(char *buf, size_t n, const char *file) { snprintf(buf, n, "%s/%s", unit_plugin_dir, file); }

static void good_plugin(void)
{
    chasm_machine *m = pt_load(PLAN);
    if (!m) return;
    CHECK(chasm_plugin_versions_loaded(m) == 1);
    chasm_start(m, 0);
    pt_set(m, "x", 1, 0);
    pt_run_until(m, 0.1, 0.3);
    CHECK(pt_get(m, "test.out") == 3.0);
    CHECK(chasm_var_updated_us(m, chasm_var_find(m, "test.out")) == 300000);
    pt_set(m, "x", 6, 0.3);
    pt_run_until(m, 0.4, 0.4);
    CHECK_STR(pt_leaf(m), "c"); /* the plugin test handler fired */
    chasm_free(m);
}

/* A new version takes effect at the next entry; the old code goes when unused. */
static void hotplug_new_version(void)
{
    chasm_machine *m = pt_load(PLAN);
    if (!m) return;
    chasm_start(m, 0);
    pt_set_bool(m, "go", 0, 0);
    pt_run_until(m, 0.1, 0.2);
    CHECK(pt_get(m, "test.out") == 3.0);
    char p[1024], err[2048];
    path_of(p, sizeof p, "chasm_test_basic_v2.so");
    int rc = chasm_hotplug(m, p, err, sizeof err);
    if (rc) fprintf(stderr, "%s\n", err);
    CHECK(rc == 0);
    CHECK(chasm_plugin_versions_loaded(m) == 2); /* state a still runs version 1 */
    pt_run_until(m, 0.3, 0.4);
    CHECK(pt_get(m, "test.out") == 3.0);
    pt_set_bool(m, "go", 1, 0.4);
    pt_run_until(m, 0.5, 0.5);
    CHECK_STR(pt_leaf(m), "b");
    CHECK(chasm_plugin_versions_loaded(m) == 1); /* version 1 unloaded on exit */
    pt_set_bool(m, "go", 0, 0.5);
    pt_run_until(m, 0.6, 0.7);
    CHECK_STR(pt_leaf(m), "a");
    CHECK(pt_get(m, "test.out") == 6.0); /* version 2 doubles */
    /* a second update of the same path gets its own handle too */
    rc = chasm_hotplug(m, p, err, sizeof err);
    CHECK(rc == 0);
    CHECK(chasm_plugin_versions_loaded(m) == 2);
    chasm_free(m);
}

/* When no active state uses the plugin, the old code goes at once. */
static void hotplug_while_unused(void)
{
    chasm_machine *m = pt_load(PLAN);
    if (!m) return;
    pt_set_bool(m, "go", 1, 0);
    chasm_start(m, 0);
    pt_run_until(m, 0.1, 0.1);
    CHECK_STR(pt_leaf(m), "b");
    char p[1024], err[2048];
    path_of(p, sizeof p, "chasm_test_basic_v2.so");
    CHECK(chasm_hotplug(m, p, err, sizeof err) == 0);
    CHECK(chasm_plugin_versions_loaded(m) == 1);
    chasm_free(m);
}

static void expect_rejected(const char *file, int write_garbage, const char *expect_in_error)
{
    chasm_machine *m = pt_load(PLAN);
    if (!m) return;
    chasm_start(m, 0);
    pt_set_bool(m, "go", 0, 0);
    pt_run_until(m, 0.1, 0.2);
    char p[1024], err[4096];
    if (write_garbage) {
        const char *tmp = getenv("TMPDIR");
        snprintf(p, sizeof p, "%s/chasm_unit_broken_%d.so", tmp && *tmp ? tmp : "/tmp", (int)getpid());
        FILE *f = fopen(p, "wb");
        if (f) {
            fputs("\177ELF this is not really a shared object", f);
            fclose(f);
        }
    } else if (file[0] == '/') snprintf(p, sizeof p, "%s", file);
    else path_of(p, sizeof p, file);
    CHECK(chasm_hotplug(m, p, err, sizeof err) == -1);
    CHECK_HAS(err, expect_in_error);
    if (write_garbage) unlink(p);
    CHECK(chasm_plugin_versions_loaded(m) == 1);
    /* the mission goes on with the old code, through re-entries too */
    pt_run_until(m, 0.3, 0.5);
    CHECK(chasm_run_state_of(m) == CHASM_RUN_RUNNING);
    CHECK(pt_get(m, "test.out") == 3.0);
    pt_set_bool(m, "go", 1, 0.5);
    pt_run_until(m, 0.6, 0.6);
    pt_set_bool(m, "go", 0, 0.6);
    pt_run_until(m, 0.7, 0.8);
    CHECK_STR(pt_leaf(m), "a");
    CHECK(pt_get(m, "test.out") == 3.0);
    chasm_free(m);
}

static void hotplug_broken_file(void) { expect_rejected(NULL, 1, "cannot load plugin file"); }
static void hotplug_missing_file(void) { expect_rejected("chasm_no_such_plugin.so", 0, "cannot read plugin file"); }
static void hotplug_wrong_abi(void) { expect_rejected("chasm_test_basic_badabi.so", 0, "built for plugin ABI 100"); }
static void hotplug_abi2(void) { expect_rejected("chasm_test_basic_abi2.so", 0,
                                                "built for plugin ABI 2, this CHASM uses ABI 3"); }
static void hotplug_schema_mismatch(void) { expect_rejected("chasm_test_basic_noschema.so", 0, "unknown parameter 'value' for 'hold'"); }
static void hotplug_missing_symbol(void) { expect_rejected("chasm_test_nosym.so", 0, "does not export the symbol 'chasm_plugin'"); }
static void hotplug_unused_plugin(void) { expect_rejected("chasm_test_other.so", 0, "is not used by the running plan"); }
/* Constructors run first in a probe process: the test process lives on. */
static void hotplug_ctor_crash(void) { expect_rejected("chasm_test_ctor_crash.so", 0, "crashed the probe process"); }
static void hotplug_ctor_exit(void) { expect_rejected("chasm_test_ctor_exit.so", 0, "ended the probe process"); }

static unsigned char *slurp(const char *path, size_t *n)
{
    FILE *f = fopen(path, "rb");
    if (!f) return NULL;
    unsigned char *b = malloc(1 << 22);
    *n = b ? fread(b, 1, 1 << 22, f) : 0;
    fclose(f);
    return b;
}

/* Every truncation of a good plugin is refused before dlopen could map it
 * (the SIGBUS class), and the whole file is accepted. */
static void every_truncation_is_refused(void)
{
    char p[1024], err[512];
    path_of(p, sizeof p, "chasm_test_basic.so");
    size_t n = 0;
    unsigned char *b = slurp(p, &n);
    CHECK(b && n > 1000);
    if (!b) return;
    CHECK(cm_elf_check(b, n, err, sizeof err) == 0);
    size_t accepted = 0;
    for (size_t cut = 0; cut < n; cut++) accepted += cm_elf_check(b, cut, err, sizeof err) == 0;
    CHECK(accepted == 0);
    free(b);
}

/* A truncated plugin through the whole hot plug: refused, mission untouched. */
static void hotplug_truncated_file(void)
{
    char src[1024], dst[1024];
    path_of(src, sizeof src, "chasm_test_basic.so");
    size_t n = 0;
    unsigned char *b = slurp(src, &n);
    if (!b) return;
    const char *tmp = getenv("TMPDIR");
    snprintf(dst, sizeof dst, "%s/chasm_unit_cut_%d.so", tmp && *tmp ? tmp : "/tmp", (int)getpid());
    FILE *f = fopen(dst, "wb");
    if (f) {
        fwrite(b, 1, n / 2, f);
        fclose(f);
    }
    free(b);
    expect_rejected(dst, 0, "truncated");
    unlink(dst);
}

const unit_test plugin_tests[] = {
    {"good_plugin", good_plugin},
    {"hotplug_new_version", hotplug_new_version},
    {"hotplug_while_unused", hotplug_while_unused},
    {"hotplug_broken_file", hotplug_broken_file},
    {"hotplug_missing_file", hotplug_missing_file},
    {"hotplug_wrong_abi", hotplug_wrong_abi},
    {"hotplug_abi2", hotplug_abi2},
    {"hotplug_schema_mismatch", hotplug_schema_mismatch},
    {"hotplug_missing_symbol", hotplug_missing_symbol},
    {"hotplug_unused_plugin", hotplug_unused_plugin},
    {"hotplug_ctor_crash", hotplug_ctor_crash},
    {"hotplug_ctor_exit", hotplug_ctor_exit},
    {"every_truncation_is_refused", every_truncation_is_refused},
    {"hotplug_truncated_file", hotplug_truncated_file},
    {NULL, NULL},
};
