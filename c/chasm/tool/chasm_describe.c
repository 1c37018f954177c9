/* `chasm describe NAME...`: what a plugin offers, for people writing plans:
 * behaviors, test handlers and every parameter with type, unit, default and
 * range, as the Loader will check them. */
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>

#include "chasm/chasm.h"
#include "chasm_describe.h"

static void print_params(const chasm_param_spec *p, size_t n)
{
    static const char *types[] = {"double", "int", "bool", "string", "messages"};
    for (size_t i = 0; i < n; i++) {
        const chasm_param_spec *s = &p[i];
        printf("      %-14s %-6s %-6s", s->name, (unsigned)s->type < 5 ? types[s->type] : "?", s->unit && *s->unit ? s->unit : "-");
        if (s->type == CHASM_MESSAGES)
            printf(" %s%s%s", s->kind == CHASM_WRITES ? "posts messages to a messages variable" : "takes each message of a messages variable once",
                   s->def_string ? ", default " : "", s->def_string ? s->def_string : "");
        else if (s->kind != CHASM_PARAM)
            printf(" %s variable%s%s", s->kind == CHASM_WRITES ? "writes" : "reads", s->def_string ? ", default " : "",
                   s->def_string ? s->def_string : "");
        else if (s->required) printf(" required");
        else if (s->flags & CHASM_SPEC_NO_DEFAULT) printf(" optional, no default");
        else if (s->type == CHASM_STRING) printf(" default \"%s\"", s->def_string ? s->def_string : "");
        else printf(" default %g", s->def_number);
        if (s->has_range) printf(", range [%g, %g]", s->min, s->max);
        if (s->doc) printf("  # %s", s->doc);
        printf("\n");
    }
}

int chasm_describe(const char *const *dirs, size_t n_dirs, const char *name)
{
    char path[4096] = "";
    int named = !strchr(name, '/');
    if (named) {
        char why[256];
        if (chasm_plugin_name_check(name, why, sizeof why)) {
            fprintf(stderr, "chasm: %s (or give a path with a '/')\n", why);
            return 1;
        }
    }
    for (size_t i = 0; named && i < n_dirs && !path[0]; i++) {
        const char *forms[] = {"%s/chasm_%s.so", "%s/%s.so"};
        for (int f = 0; f < 2 && !path[0]; f++) {
            snprintf(path, sizeof path, forms[f], dirs[i], name);
            struct stat st;
            if (lstat(path, &st)) path[0] = 0;
        }
    }
    if (!named) snprintf(path, sizeof path, "%s", name);
    if (!path[0]) {
        fprintf(stderr, "chasm: plugin '%s' not found in the plugin path\n", name);
        return 1;
    }
    /* the same checked, probed load as the Loader's: any file may be given here */
    char err[2048];
    chasm_plugin_file *pf = chasm_plugin_file_open(path, NULL, err, sizeof err);
    if (!pf) {
        if (strstr(err, "does not export the symbol"))
            fprintf(stderr, "chasm: '%s' does not export '%s'\n", path, CHASM_PLUGIN_SYMBOL);
        else fprintf(stderr, "chasm: %s\n", err);
        return 1;
    }
    const chasm_plugin_descriptor *d = chasm_plugin_file_descriptor(pf);
    printf("plugin %s %s (%s)\n", d->name, d->version, path);
    for (size_t i = 0; i < d->n_behaviors; i++) {
        printf("  behavior %s%s%s\n", d->behaviors[i].name, d->behaviors[i].doc ? ": " : "",
               d->behaviors[i].doc ? d->behaviors[i].doc : "");
        print_params(d->behaviors[i].params, d->behaviors[i].n_params);
    }
    for (size_t i = 0; i < d->n_tests; i++) {
        printf("  test handler %s%s%s\n", d->tests[i].name, d->tests[i].doc ? ": " : "",
               d->tests[i].doc ? d->tests[i].doc : "");
        print_params(d->tests[i].params, d->tests[i].n_params);
    }
    chasm_plugin_file_close(pf);
    return 0;
}
