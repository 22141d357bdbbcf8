#pragma once
// Idle OpenMP threads that spin take the cores llvmpipe's own threads need (43 % of a profiled
// lzb run was libgomp's spin loop), so lzb runs with OMP_WAIT_POLICY=passive unless the user
// set a policy. libgomp reads it before main, so the process re-executes itself once with it set.
namespace lzb {

// Call first thing in main, before MPI starts; returns only if no re-execution happened.
void preferPassiveOmpWait(char** argv);

}  // namespace lzb
