#pragma once
// Any failure on any rank ends the whole job, promptly, with the message and a non-zero status
// (2 for bad input, 1 otherwise); never a hang.
//
// Steps that every rank runs alike (parsing, loading, building) are wrapped in agree(): each rank
// runs the step, then all agree on the outcome with one collective. When a rank failed, every
// rank leaves with JobFailed and the root prints each failing rank's message once (so a bad
// input given to all ranks gives one clean message and exit status 2 from mpirun). A failed rank
// whose peers do not reach the agreement within kAgreeSeconds (they may be stuck in other work,
// or in a collective the failed rank never joins) aborts the job with MPI_Abort and its status.
// Inside a frame, where ranks meet in collectives at every step, a failing rank aborts at once.
#include <functional>
#include <stdexcept>
#include <string>

#include "mpi/group.hpp"

namespace lzb::mpi {

// Every rank leaves the program with this status; the messages have been printed.
class JobFailed : public std::runtime_error {
 public:
  explicit JobFailed(int status) : std::runtime_error("job failed"), status(status) {}
  int status;
};

constexpr double kAgreeSeconds = 5.0;

// Exit status of an exception: 2 for InputError (bad input), 1 otherwise.
int statusOf(const std::exception& e);
// The one-line message lzb prints for an exception (without the "lzb: " prefix).
std::string messageOf(const std::exception& e);

// Runs step() on this rank and agrees with every rank on the outcome (see above). Steps nest: a
// step agreed on inside step() (its JobFailed) fails this one with its status, printed once.
void agree(const Group& g, const std::function<void()>& step);

// Prints this rank's message and ends every rank of a multi-rank job (MPI_Abort with the status).
[[noreturn]] void abortJob(const Group& g, const std::exception& e);

}  // namespace lzb::mpi
