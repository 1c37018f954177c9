/* One reader of the protocols' hostile corpora (corpus_expect.h). */
#include "corpus_expect.h"

#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "../harness/unit.h"

static void check_figures(const char *file, char *expect, void *rig, const corpus_rig *c)
{
    for (char *tok = strtok(expect, " "); tok; tok = strtok(NULL, " ")) {
        char *eq = strrchr(tok, '=');
        CHECK(eq != NULL);
        if (!eq)
            continue;
        *eq = '\0';
        for (char *ch = tok; *ch; ch++)
            if (*ch == '_')
                *ch = ' ';
        long want = strtol(eq + 1, NULL, 10), got = c->figure(rig, tok);
        if (got != want)
            fprintf(stderr, "%s: %s: want %ld, got %ld (last error: %s)\n", file, tok, want, got, c->last_error(rig));
        CHECK(got == want);
    }
}

int corpus_check(const char *dir, const corpus_rig *c)
{
    DIR *d = opendir(dir);
    CHECK(d != NULL);
    if (!d)
        return 0;
    int files = 0;
    struct dirent *ent;
    while ((ent = readdir(d))) {
        if (ent->d_name[0] == '.')
            continue;
        char path[512];
        snprintf(path, sizeof path, "%s/%s", dir, ent->d_name);
        FILE *f = fopen(path, "rb");
        CHECK(f != NULL);
        if (!f)
            continue;
        static uint8_t data[1 << 17];
        size_t n = fread(data, 1, sizeof data, f);
        fclose(f);
        CHECK(n > 9 && !memcmp(data, "# expect:", 9));
        size_t head = 9;
        while (head < n && data[head] != '\n')
            head++;
        char expect[512];
        snprintf(expect, sizeof expect, "%.*s", (int)(head - 9), (const char *)data + 9);
        void *rig = c->open();
        size_t k = 0;
        for (size_t i = head + 1; i < n; i += c->read_size, k++)
            c->read(rig, data + i, n - i < c->read_size ? n - i : c->read_size, k);
        if (c->end)
            c->end(rig, k);
        check_figures(ent->d_name, expect, rig, c);
        free(rig);
        files++;
    }
    closedir(d);
    return files;
}
