// The last few seconds of measurements, each with the filter state just
// after it, oldest first: what lets a late measurement (an LBL reply stamped
// with its ping time, a message overtaken on the network) be processed in
// time order. A fixed ring allocated once; inserting in the middle shifts
// the younger entries, which happens only for late arrivals.
#ifndef NAV_HISTORY_HPP
#define NAV_HISTORY_HPP

#include <cstddef>
#include <vector>

#include "nav/ekf_state.hpp"

namespace nav {

struct HistoryEntry {
    Measurement m;
    FilterState post;           // the state after m was processed
};

class History {
public:
    explicit History(size_t capacity);
    size_t size() const { return count_; }
    size_t capacity() const { return buf_.size(); }
    HistoryEntry &at(size_t i) { return buf_[(head_ + i) % buf_.size()]; }
    const HistoryEntry &at(size_t i) const { return buf_[(head_ + i) % buf_.size()]; }
    // Append at the young end; a full ring forgets its oldest entry.
    void push_back(const Measurement &m, const FilterState &post);
    // Insert before logical index i (0 = oldest). A full ring forgets its
    // oldest entry first; returns false if that was where i pointed.
    bool insert(size_t i, const Measurement &m, const FilterState &post);
    void pop_front();
    // Number of entries with utime <= t (so the insertion index for t).
    size_t count_at_or_before(int64_t t) const;

private:
    std::vector<HistoryEntry> buf_;
    size_t head_ = 0, count_ = 0;
};

}  // namespace nav

#endif
