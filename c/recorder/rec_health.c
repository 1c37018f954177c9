#include "recorder/rec_health.h"

#include <string.h>
#include <sys/resource.h>
#include <time.h>
#include <unistd.h>

#include "auv/auv_process_health_t.h"

static double wall_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + ts.tv_nsec * 1e-9;
}

static double cpu_s(void)
{
    struct rusage ru;
    getrusage(RUSAGE_SELF, &ru);
    return (double)(ru.ru_utime.tv_sec + ru.ru_stime.tv_sec) + (ru.ru_utime.tv_usec + ru.ru_stime.tv_usec) * 1e-6;
}

void rec_health_init(rec_health *h)
{
    h->last_wall = wall_s();
    h->last_cpu = cpu_s();
}

void rec_health_publish(rec_health *h, lcm_t *lcm, const char *name, int64_t utime,
                        int64_t received, int64_t lost)
{
    double w = wall_s(), c = cpu_s();
    auv_process_health_t m;
    memset(&m, 0, sizeof m);
    m.utime = utime;
    m.vehicle = "";
    m.process = (char *)name;
    m.pid = (int32_t)getpid();
    m.messages_received = received;
    m.decode_errors = 0;
    m.queue_overflows = lost;
    m.cpu_load = w > h->last_wall ? (c - h->last_cpu) / (w - h->last_wall) : 0.0;
    h->last_wall = w;
    h->last_cpu = c;
    auv_process_health_t_publish(lcm, "SIM.HEALTH", &m);
}
