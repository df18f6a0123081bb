// peer_result.h — what a peer library (FCL, libccd) answers for one pair: its rigid PD.
//
// Peers are other people's penetration-depth code, run on the same pairs as ours for the
// `pdd bench` time ratios and error columns (peer_fcl.h, peer_ccd.h). A peer that reports
// "not intersecting" on a pair the exact engine calls intersecting, or a non-finite depth, or
// an error code, is a failure of the peer on that pair: counted and reported, never filtered.
#pragma once

namespace pdd::compare {

enum class PeerStatus {
  Intersecting,     // pd is the peer's penetration depth (> 0, or 0 for a touching contact)
  NotIntersecting,  // the peer found no intersection; pd = 0
  Failed,           // error code from the peer, or a non-finite depth; pd = NaN
};

struct PeerDepth {
  PeerStatus status = PeerStatus::Failed;
  double pd = 0.0;  // PD, not squared
};

}  // namespace pdd::compare
