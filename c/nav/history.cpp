#include "nav/history.hpp"

namespace nav {

History::History(size_t capacity) : buf_(capacity > 0 ? capacity : 1) {}

void History::push_back(const Measurement &m, const FilterState &post)
{
    if (count_ == buf_.size())
        pop_front();
    HistoryEntry &e = at(count_++);
    e.m = m;
    e.post = post;
}

bool History::insert(size_t i, const Measurement &m, const FilterState &post)
{
    if (count_ == buf_.size()) {
        if (i == 0)
            return false;
        pop_front();
        i--;
    }
    for (size_t j = count_; j > i; j--)
        at(j) = at(j - 1);
    count_++;
    at(i).m = m;
    at(i).post = post;
    return true;
}

void History::pop_front()
{
    if (count_ == 0)
        return;
    head_ = (head_ + 1) % buf_.size();
    count_--;
}

size_t History::count_at_or_before(int64_t t) const
{
    // entries are in time order: binary search for the first one after t
    size_t lo = 0, hi = count_;
    while (lo < hi) {
        size_t mid = (lo + hi) / 2;
        if (at(mid).m.utime <= t)
            lo = mid + 1;
        else
            hi = mid;
    }
    return lo;
}

}  // namespace nav
