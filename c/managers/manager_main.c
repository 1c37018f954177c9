/* chasm-manager: run one CHASM mission plan as a manager process. This file
 * only parses the command line and runs the manager (manager.h).
 *
 *   chasm-manager --plan navigator.chasm --bind vehicle.bind --vehicle AUV1 --name NAVIGATOR
 *                 [--rate 10] [--clock sim|system] [--lcm-url URL] [--exit-on-end] [--wait-start]
 *                 [--plugin-path DIR]... [--plugin-dir DIR --allowlist FILE] [-D name=value]...
 *
 * Each cycle (rate_hz on the mission clock): chasm_step(), then the plan's
 * outputs are published and its status goes to <VEHICLE>.CHASM.<NAME>. With
 * --clock sim the mission clock is SIM.CLOCK (nothing runs until it ticks);
 * with --clock system it is the host's clock. SIGINT/SIGTERM end the process
 * after the current cycle. A plan starts once every input channel it binds
 * has delivered a message, except inputs bound `optional` (until then its
 * status says LOADING). Exit status: 0 done or stopped, 1 load error,
 * 2 usage or LCM error, 3 aborted, 4 failed (with --exit-on-end). */
#include <signal.h>
#include <string.h>

#include "managers/manager.h"

static manager_t *g_mg;

static void on_signal(int sig)
{
    (void)sig;
    if (g_mg)
        manager_request_stop(g_mg);
}

int main(int argc, char **argv)
{
    static manager_options opt;
    int pa = manager_parse_args(&opt, argc, argv);
    if (pa != 0)
        return pa > 0 ? 0 : 2;
    static manager_t mg; /* static: handlers keep pointers into it */
    int rc = manager_create(&mg, &opt);
    if (rc != 0)
        return rc;
    g_mg = &mg;
    struct sigaction sa;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_signal;
    sigaction(SIGINT, &sa, NULL);
    sigaction(SIGTERM, &sa, NULL);
    rc = manager_run(&mg);
    manager_destroy(&mg);
    return rc;
}
