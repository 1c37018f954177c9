/* `chasm describe NAME...`: what a plugin offers, for people writing plans:
 * behaviors, test handlers and every parameter with type, unit, default and
 * range, as the Loader will check them. */
#include <dlfcn.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>

#include "chasm/chasm_plugin.h"
#include "chasm_describe.h"

static void print_params(const chasm_param_spec *p, size_t n)
{
    static const char *types[] = {"double", "int", "bool", "string"};
    for (size_t i = 0; i < n; i++) {
        const chasm_param_spec *s = &p[i];
        printf("      %-14s %-6s %-6s", s->name, (unsigned)s->type < 4 ? types[s->type] : "?", s->unit && *s->unit ? s->unit : "-");
        if (s->kind != CHASM_PARAM)
            printf(" %s variable%s%s", s->kind == CHASM_WRITES ? "writes" : "reads", s->def_string ? ", default " : "",
                   s->def_string ? s->def_string : "");
        else if (s->required) printf(" required");
        else if (s->type == CHASM_STRING) printf(" default \"%s\"", s->def_string ? s->def_string : "");
        /* A default outside the range can never be given: the plugin uses it to
         * mean "absent" (one of two forms, a box or a polygon). */
        else if (s->has_range && (s->def_number < s->min || s->def_number > s->max)) printf(" optional, no default");
        else printf(" default %g", s->def_number);
        if (s->has_range) printf(", range [%g, %g]", s->min, s->max);
        if (s->doc) printf("  # %s", s->doc);
        printf("\n");
    }
}

int chasm_describe(const char *const *dirs, size_t n_dirs, const char *name)
{
    char path[4096] = "";
    for (size_t i = 0; i < n_dirs && !path[0]; i++) {
        const char *forms[] = {"%s/chasm_%s.so", "%s/%s.so"};
        for (int f = 0; f < 2 && !path[0]; f++) {
            snprintf(path, sizeof path, forms[f], dirs[i], name);
            if (access(path, R_OK)) path[0] = 0;
        }
    }
    if (!path[0] && strchr(name, '/')) snprintf(path, sizeof path, "%s", name);
    if (!path[0]) {
        fprintf(stderr, "chasm: plugin '%s' not found in the plugin path\n", name);
        return 1;
    }
    void *dl = dlopen(path, RTLD_NOW | RTLD_LOCAL);
    if (!dl) {
        fprintf(stderr, "chasm: %s\n", dlerror());
        return 1;
    }
    const chasm_plugin_descriptor *d = dlsym(dl, CHASM_PLUGIN_SYMBOL);
    int rc = 0;
    if (!d) {
        fprintf(stderr, "chasm: '%s' does not export '%s'\n", path, CHASM_PLUGIN_SYMBOL);
        rc = 1;
    } else if (d->abi_version != CHASM_PLUGIN_ABI || d->struct_size != sizeof *d) {
        fprintf(stderr, "chasm: '%s' was built for plugin ABI %u, this CHASM uses ABI %d\n", path, d->abi_version,
                CHASM_PLUGIN_ABI);
        rc = 1;
    } else {
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
    }
    dlclose(dl);
    return rc;
}
