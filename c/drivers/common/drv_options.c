#include "drivers/common/drv_options.h"

#include <stdlib.h>
#include <string.h>

#include "drivers/common/drv_port.h"

void drv_options_usage(FILE *out, const drv_protocol *p)
{
    fprintf(out,
            "usage: %s (--device PATH [--baud N] | --tcp HOST:PORT) --vehicle ID [options]\n\n%s\n\n"
            "  --device PATH      serial device (raw mode, 8N1, no flow control)\n"
            "  --baud N           its baud rate (default %d; 1200 .. 921600)\n"
            "  --tcp HOST:PORT    a TCP port instead (a serial server, a networked device)\n"
            "  --vehicle ID       the vehicle: channels <ID>.%s, <ID>.DRIVER.%s, <ID>.HEALTH\n"
            "  --lcm-url URL      LCM URL (default: liblcm's, $LCM_DEFAULT_URL)\n"
            "  --raw              also publish the bytes read and written on <ID>.RAW.%s (raw_bytes_t)\n"
            "  --clock MODE       system (default): stamps are CLOCK_REALTIME; sim: the newest SIM.CLOCK\n"
            "                     (a simulated vehicle; bytes before the first clock are dropped, counted)\n",
            p->program, p->summary, p->default_baud, p->device, p->device, p->device);
    for (const drv_subscription *s = p->subscriptions; s && s->suffix; s++)
        fprintf(out, "  %-18s <ID>.%s (%s): the driver's LCM input\n", "(subscribes)", s->suffix, s->type_name);
    for (const drv_flag *f = p->flags; f && f->name; f++) {
        char head[64];
        snprintf(head, sizeof head, "%s%s%s", f->name, f->arg ? " " : "", f->arg ? f->arg : "");
        fprintf(out, "  %-18s %s\n", head, f->help);
    }
    fprintf(out, "  --help             this text\n\nSee docs/drivers.md.\n");
}

static int usage_error(const drv_protocol *p, const char *msg, const char *what)
{
    fprintf(stderr, "%s: %s%s\n(see %s --help)\n", p->program, msg, what ? what : "", p->program);
    return 2;
}

int drv_options_parse(drv_options *o, const drv_protocol *p, void *state, int argc, char **argv)
{
    memset(o, 0, sizeof *o);
    o->baud = p->default_baud;
    o->clock = DRV_CLOCK_SYSTEM;
    int baud_given = 0;
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        if (!strcmp(a, "--help") || !strcmp(a, "-h")) {
            drv_options_usage(stdout, p);
            return 1;
        }
        if (!strcmp(a, "--raw")) {
            o->raw = 1;
            continue;
        }
        /* the driver's own flags first: they may not shadow the common ones */
        const drv_flag *own = NULL;
        for (const drv_flag *f = p->flags; f && f->name; f++)
            if (!strcmp(a, f->name))
                own = f;
        const char *v = NULL;
        int takes_value = own ? own->arg != NULL : 1;
        if (takes_value) {
            if (i + 1 >= argc)
                return usage_error(p, a, " needs a value");
            v = argv[++i];
        }
        if (own) {
            char err[256] = "";
            if (own->set(state, v, err, sizeof err) < 0)
                return usage_error(p, err[0] ? err : "bad value for ", err[0] ? NULL : a);
        } else if (!strcmp(a, "--device")) {
            o->device_path = v;
        } else if (!strcmp(a, "--baud")) {
            char *end;
            long b = strtol(v, &end, 10);
            if (*end || !drv_port_baud_ok((int)b) || b != (int)b)
                return usage_error(p, "--baud must be one of 1200 2400 4800 9600 19200 38400 57600 115200 230400 "
                                      "460800 921600, not ", v);
            o->baud = (int)b;
            baud_given = 1;
        } else if (!strcmp(a, "--tcp")) {
            o->tcp = v;
        } else if (!strcmp(a, "--vehicle")) {
            o->vehicle = v;
        } else if (!strcmp(a, "--lcm-url") || !strcmp(a, "--url")) {
            o->lcm_url = v;
        } else if (!strcmp(a, "--clock")) {
            if (!strcmp(v, "system"))
                o->clock = DRV_CLOCK_SYSTEM;
            else if (!strcmp(v, "sim") && p->clock_source)
                return usage_error(p, "--clock sim: this driver is the vehicle's clock source (it publishes "
                                      "SIM.CLOCK); it runs on the system clock", NULL);
            else if (!strcmp(v, "sim"))
                o->clock = DRV_CLOCK_SIM;
            else
                return usage_error(p, "--clock is system or sim, not ", v);
        } else {
            return usage_error(p, "unknown option ", a);
        }
    }
    if (!o->device_path == !o->tcp)
        return usage_error(p, "give exactly one of --device PATH and --tcp HOST:PORT", NULL);
    if (o->tcp && baud_given)
        return usage_error(p, "--baud is for --device, not --tcp", NULL);
    if (!o->vehicle || !o->vehicle[0])
        return usage_error(p, "--vehicle ID is required", NULL);
    for (const char *c = o->vehicle; *c; c++)
        if (!((*c >= 'A' && *c <= 'Z') || (*c >= 'a' && *c <= 'z') || (*c >= '0' && *c <= '9') || *c == '_' ||
              *c == '-'))
            return usage_error(p, "--vehicle is letters, digits, '_' and '-', not ", o->vehicle);
    return 0;
}
