// Threads that stay up between parallel_for calls. A click at millions of Gaussians makes
// hundreds of short parallel passes; a fresh std::thread per pass reached its first task
// 100-170 us after the call on the dev VMs (clone, a new stack's page faults, a sleeping
// vCPU woken), so a pass of a millisecond or two ran mostly on the calling thread. Pool
// threads wait for the next pass by spinning briefly, then sleeping on a futex.
#pragma once

#include <functional>

namespace isegman {

// Runs body(w) for every w in [0, workers): w = 0 on the calling thread, the others on pool
// threads, and returns when all have returned. `body` must not throw. Returns false without
// running anything when the pool cannot take the call: it is serving another one (a
// parallel_for inside a task, or one on another thread), `workers` is above what the pool
// keeps (2 or the cores, whichever is more), a thread cannot be started, or the process is
// a fork of the one that started the threads. The caller then starts threads of its own.
bool run_on_pool(int workers, const std::function<void(int)>& body);

}  // namespace isegman
