// Settings that the C library and OpenMP read only when a process starts, applied by
// restarting the process once (execv of /proc/self/exe with the same arguments).
#pragma once

namespace isegman {

// Restarts the process once (`executable`: the running program; tests give another) with
// the settings below added to its environment, where they are not set already; returns
// only when nothing was missing or the restart failed (then the process carries on as it
// is).
// - OMP_WAIT_POLICY=PASSIVE: spinning OpenMP workers make libtorch about 10x slower on
//   shared 2-core machines.
// - GLIBC_TUNABLES glibc.malloc.hugetlb=1: malloc advises its large blocks as transparent
//   huge pages. A page fault is costly on the VMs this runs on, and a scene, a view's frame
//   and its vote arrays are tens to hundreds of MB first written in 4 KiB pages; at 6M
//   Gaussians the PLY load took 7.2 s and building 20 views 93 s, with it 1.3 s and 45 s.
//   A user's own glibc.malloc.hugetlb setting (0 switches it off) is kept.
void restart_with_process_settings(char** argv, const char* executable = "/proc/self/exe");

}  // namespace isegman
