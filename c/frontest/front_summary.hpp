// The compact front summary of the team link (message `front` of
// c/plugins/team/team_link.schema, 16 bytes): a vehicle's own estimate,
// quantised for the acoustic modem, and back into a prior for a teammate's
// fit (front_fit.hpp, Prior).
//
// Sending: the parameters are rounded to their steps by the codec; the sigmas
// are first rounded up to theirs (a quantised sigma never claims more than
// the fit), the two waters' sigmas sent as the larger; the sample count
// saturates. Only an OK straight-or-meandering estimate is summarised (its
// straight part: the meander is not sent), and one outside the schema's
// ranges (a sigma over 25.5 m, a width over 409.5 m) is not sent at all.
// Receiving: each sigma grows by its parameter's quantisation, step^2 / 12.
#ifndef FRONTEST_FRONT_SUMMARY_HPP
#define FRONTEST_FRONT_SUMMARY_HPP

#include <cstddef>
#include <cstdint>
#include <vector>

extern "C" {
#include "team/team_codec.h"
#include "teamlink/team_front.h"
}

#include "frontest/front_fit.hpp"

namespace frontest {

// The summary of an OK estimate by team member `vehicle` at mission time
// `mission_s`; false when there is none to send (not OK, or out of range).
bool to_summary(const FitResult &r, int vehicle, double mission_s, team_msg_front &out);
// A teammate's summary as a prior.
Prior from_summary(const team_msg_front &m);
// The front summaries of a team-link frame (a frame that does not decode
// gives those before the fault; *bad is set).
std::vector<team_msg_front> fronts_in_frame(const uint8_t *data, size_t len, bool *bad = nullptr);

}  // namespace frontest

#endif
