// The time-ordering ring: insertion keeps time order, a full ring forgets
// its oldest entry, and the search finds the insertion point.
#include "../../harness/unit.h"
#include "nav/history.hpp"

static nav::Measurement at(int64_t t)
{
    nav::Measurement m{};
    m.utime = t;
    m.sensor = nav::SENSOR_DEPTH;
    return m;
}

TEST(history_keeps_time_order_and_capacity)
{
    nav::History h(4);
    nav::FilterState s;
    for (int64_t t : {10, 20, 30})
        h.push_back(at(t), s);
    CHECK(h.count_at_or_before(5) == 0);
    CHECK(h.count_at_or_before(20) == 2);
    CHECK(h.count_at_or_before(25) == 2);
    CHECK(h.count_at_or_before(99) == 3);
    CHECK(h.insert(2, at(25), s));          // 10 20 25 30
    CHECK(h.size() == 4 && h.at(2).m.utime == 25 && h.at(3).m.utime == 30);
    CHECK(h.insert(1, at(15), s));          // full: forgets 10 -> 15 20 25 30
    CHECK(h.size() == 4 && h.at(0).m.utime == 15 && h.at(1).m.utime == 20);
    CHECK(!h.insert(0, at(1), s));          // older than everything kept, ring full
    h.push_back(at(40), s);                 // 20 25 30 40
    CHECK(h.at(0).m.utime == 20 && h.at(3).m.utime == 40);
    h.pop_front();
    CHECK(h.size() == 3 && h.at(0).m.utime == 25);
}
