/* The address table of the Micro-Modem bridge: which modem address each
 * vehicle's modem answers to ("AUV1=1,AUV2=2"). The modem knows addresses,
 * the team link knows vehicle ids; every vehicle of a team reads the same
 * table, so the mapping is the same on every side. */
#include <ctype.h>
#include <stdlib.h>
#include <string.h>

#include "drivers/modem/mm_bridge.h"

int mm_table_parse(mm_table *t, const char *spec, const char **why)
{
    memset(t, 0, sizeof *t);
    const char *p = spec;
    while (*p) {
        const char *end = strchr(p, ',');
        size_t len = end ? (size_t)(end - p) : strlen(p);
        const char *eq = memchr(p, '=', len);
        if (!eq || eq == p) {
            *why = "an entry is not NAME=ADDRESS";
            return -1;
        }
        size_t nlen = (size_t)(eq - p);
        if (nlen >= MM_NAME_MAX) {
            *why = "a vehicle name is too long";
            return -1;
        }
        for (size_t i = 0; i < nlen; i++)
            if (!isalnum((unsigned char)p[i]) && p[i] != '_' && p[i] != '-') {
                *why = "a vehicle name has a character other than letters, digits, _ and -";
                return -1;
            }
        const char *num = eq + 1, *num_end = p + len;
        long a = 0;
        if (num == num_end) {
            *why = "an entry has no address";
            return -1;
        }
        for (const char *q = num; q < num_end; q++) {
            if (!isdigit((unsigned char)*q) || a > MM_MAX_ADDRESS) {
                *why = "an address is not a number in 1..127";
                return -1;
            }
            a = a * 10 + (*q - '0');
        }
        if (a < 1 || a > MM_MAX_ADDRESS) {
            *why = "an address is not a number in 1..127 (0 is the broadcast address)";
            return -1;
        }
        if (t->n == MM_TABLE_MAX) {
            *why = "more than 32 entries";
            return -1;
        }
        for (int i = 0; i < t->n; i++) {
            if (t->address[i] == a) {
                *why = "an address is given twice";
                return -1;
            }
            if (strlen(t->vehicle[i]) == nlen && !memcmp(t->vehicle[i], p, nlen)) {
                *why = "a vehicle is given twice";
                return -1;
            }
        }
        memcpy(t->vehicle[t->n], p, nlen);
        t->vehicle[t->n][nlen] = 0;
        t->address[t->n++] = (int)a;
        if (!end)
            break;
        p = end + 1;
        if (!*p) {
            *why = "an entry is not NAME=ADDRESS";
            return -1;
        }
    }
    if (t->n == 0) {
        *why = "the table is empty";
        return -1;
    }
    return 0;
}

int mm_table_address(const mm_table *t, const char *vehicle)
{
    for (int i = 0; i < t->n; i++)
        if (!strcmp(t->vehicle[i], vehicle))
            return t->address[i];
    return -1;
}

const char *mm_table_vehicle(const mm_table *t, int address)
{
    for (int i = 0; i < t->n; i++)
        if (t->address[i] == address)
            return t->vehicle[i];
    return NULL;
}
