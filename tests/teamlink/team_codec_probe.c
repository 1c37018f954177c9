/* The generated C codec driven from text, for the Python cross tests
 * (tests/teamlink/test_team_cross.py).
 *
 *   team-codec-probe encode MAX_BYTES   each stdin line "name v v ...; name v ...":
 *                                       prints "HEX REFUSED" (refused messages skipped)
 *   team-codec-probe decode             each stdin line a hex frame: prints
 *                                       "name v v ...;" per message then "| RC LEFT_BITS"
 * Values are printed with %.17g so Python reads back the exact doubles. */
#include "team/team_codec.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static int parse_message(char *text, team_msg *m)
{
    char *save = NULL;
    char *name = strtok_r(text, " \t", &save);
    if (!name)
        return -1;
    const team_message_info *info = team_message_by_name(name);
    if (!info)
        return TEAM_ERR_UNKNOWN_ID;
    memset(m, 0, sizeof *m);
    m->id = info->id;
    for (size_t i = 0; i < info->n_fields; i++) {
        char *tok = strtok_r(NULL, " \t", &save);
        if (!tok)
            return -1;
        char *field = (char *)&m->u + info->fields[i].offset;
        if (info->fields[i].is_int) {
            long long v = strtoll(tok, NULL, 10);
            int32_t v32 = (int32_t)v;
            memcpy(field, &v32, sizeof v32);
        } else {
            double v = strtod(tok, NULL);
            memcpy(field, &v, sizeof v);
        }
    }
    return 0;
}

static int encode(size_t max_bytes)
{
    char line[8192];
    uint8_t *frame = malloc(max_bytes ? max_bytes : 1);
    while (fgets(line, sizeof line, stdin)) {
        line[strcspn(line, "\n")] = '\0';
        team_bits w;
        team_bits_writer(&w, frame, max_bytes);
        int refused = 0;
        char *save = NULL;
        for (char *part = strtok_r(line, ";", &save); part; part = strtok_r(NULL, ";", &save)) {
            team_msg m;
            if (parse_message(part, &m) != 0 || team_msg_encode(&m, &w) != TEAM_OK)
                refused++;
        }
        size_t n = team_bits_bytes(&w);
        for (size_t i = 0; i < n; i++)
            printf("%02x", frame[i]);
        printf("%s %d\n", n ? "" : "-", refused);
    }
    free(frame);
    return 0;
}

static int decode(void)
{
    char line[8192];
    while (fgets(line, sizeof line, stdin)) {
        line[strcspn(line, "\n")] = '\0';
        size_t n = strlen(line) / 2;
        /* Exactly n bytes on the heap, so ASan sees any read past the frame. */
        uint8_t *frame = malloc(n ? n : 1);
        for (size_t i = 0; i < n; i++) {
            unsigned v = 0;
            sscanf(line + 2 * i, "%2x", &v);
            frame[i] = (uint8_t)v;
        }
        team_bits r;
        team_bits_reader(&r, frame, n);
        team_msg m;
        int rc;
        while ((rc = team_decode_next(&r, &m)) > 0) {
            const team_message_info *info = team_message_by_id(rc);
            printf("%s", info->name);
            for (size_t i = 0; i < info->n_fields; i++) {
                const char *field = (const char *)&m.u + info->fields[i].offset;
                if (info->fields[i].is_int) {
                    int32_t v;
                    memcpy(&v, field, sizeof v);
                    printf(" %d", (int)v);
                } else {
                    double v;
                    memcpy(&v, field, sizeof v);
                    printf(" %.17g", v);
                }
            }
            printf(";");
        }
        printf("| %d %zu\n", rc, rc < 0 ? team_bits_left(&r) : (size_t)0);
        free(frame);
    }
    return 0;
}

int main(int argc, char **argv)
{
    setvbuf(stdout, NULL, _IOFBF, 1 << 16);
    if (argc == 3 && strcmp(argv[1], "encode") == 0)
        return encode((size_t)strtoul(argv[2], NULL, 10));
    if (argc == 2 && strcmp(argv[1], "decode") == 0)
        return decode();
    fprintf(stderr, "usage: team-codec-probe encode MAX_BYTES | decode\n");
    return 2;
}
