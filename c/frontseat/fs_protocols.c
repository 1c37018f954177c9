/* The frontseat protocols auv-frontseat speaks (--protocol): one line each. */
#include <string.h>
#include <strings.h>

#include "frontseat/frontseat.h"

static const fs_proto *const protocols[] = {
    &iver3_proto,
    &bluefin_proto,
};

const fs_proto *fs_proto_find(const char *name)
{
    for (size_t i = 0; i < sizeof protocols / sizeof *protocols; i++)
        if (!strcasecmp(protocols[i]->name, name))
            return protocols[i];
    return NULL;
}

const char *fs_proto_names(void) { return "iver3, bluefin"; }
