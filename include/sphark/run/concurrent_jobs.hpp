#pragma once
// Independent jobs (the runs of a scene, the members of an ensemble) spread over `lanes`
// threads, each job's own OpenMP loops on `threads_per_lane` threads: small runs that scale
// poorly with threads (a 2,000-particle drop gains 1.2x from a second thread) finish sooner side
// by side, one thread each, than one after the other on all of them.
//
// Jobs are taken in index order; a lane takes no new job once stop_requested() (SIGINT/SIGTERM)
// or once a job returned false (a failure: the jobs in progress finish, no new one starts).
// An exception thrown by a job is kept (the first one) and rethrown on the calling thread after
// every lane has ended: none escapes a lane. With one lane the jobs run on the calling thread.
#include <cstddef>
#include <functional>

namespace sphark {

// `job(i)` for i = 0 .. count-1 (each index once, unless stopped); returns how many started.
// job returns false to stop the others from starting new jobs.
std::size_t run_concurrently(std::size_t count, int lanes, int threads_per_lane,
                             const std::function<bool(std::size_t)>& job);

}  // namespace sphark
