// mosb's fork server: the small program that forks the parked children of one job's queries
// (launch.hpp) on mosb's request. A fork costs in proportion to the forking process's mappings,
// and mosb maps every library of every command (some 430 mappings; this program, linked
// statically, a dozen): a parked child and its PID namespace's init forked from here cost a
// tenth of what they cost forked from mosb (BENCHMARKS.md). lib/run carries this program's bytes
// (fork_server_image.cpp) and starts it from memory, so nothing has to be found on disk.
//
//   PROGRAM MOSB_PID NOFILE_SOFT NOFILE_HARD    (file descriptor 3: the request socket)
//
// Each child is made mosb's (CLONE_PARENT): mosb waits for it, signals it and reaps it as if it
// had forked it itself. The server ends when mosb closes the socket, or with mosb.

#include <sched.h>
#include <sys/prctl.h>
#include <sys/socket.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <string>

#include "launch.hpp"

using namespace mosb::run_internal;

namespace {

constexpr int kSocket = 3;

// One request: its header, the queries directory and its descriptors (received close-on-exec).
struct Request {
  ParkRequest header;
  char directory[kMaxDirectory + 1] = {};
  int fds[kMaxDescriptors] = {-1, -1, -1, -1};
  std::size_t count = kMaxDescriptors;
};

// The next request into `r`, or false at the socket's end or when the request is malformed.
bool receive(Request& r) {
  char bytes[sizeof(ParkRequest) + kMaxDirectory];
  const ssize_t got = receive_with_descriptors(kSocket, bytes, sizeof bytes, r.fds, r.count);
  if (got <= 0) return false;
  const auto size = static_cast<std::size_t>(got);
  if (size < sizeof r.header) return false;
  std::memcpy(&r.header, bytes, sizeof r.header);
  if (r.header.directory_size > kMaxDirectory ||
      size != sizeof r.header + r.header.directory_size ||
      r.count != 2U + (r.header.has_procs != 0) + (r.header.has_network != 0))
    return false;
  std::memcpy(r.directory, bytes + sizeof r.header, r.header.directory_size);
  return true;
}

// The parked child of `r`, a child of mosb: its pid, or -1 with errno set.
pid_t park(Request& r, pid_t mosb) {
  const int procs = r.header.has_procs != 0 ? r.fds[2] : -1;
  const int network = r.header.has_network != 0 ? r.fds[r.count - 1] : -1;
  SealSetup seal(r.header.sealed != 0, r.directory, network);
  // A fork whose child's parent is this process's: the system call, since glibc has no wrapper
  // that takes CLONE_PARENT without a stack of the caller's.
  const auto child =
      static_cast<pid_t>(::syscall(SYS_clone, CLONE_PARENT, nullptr, nullptr, nullptr, nullptr));
  if (child == 0) {
    ::close(kSocket);
    parked_child(r.fds[0], r.fds[1], procs, mosb, r.header.pid_namespace != 0, seal);
  }
  return child;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 4) return 2;
  const auto mosb = static_cast<pid_t>(std::strtol(argv[1], nullptr, 10));
  started_file_limit.rlim_cur = std::strtoull(argv[2], nullptr, 10);
  started_file_limit.rlim_max = std::strtoull(argv[3], nullptr, 10);
  ::prctl(PR_SET_PDEATHSIG, SIGKILL, 0, 0, 0);
  if (::getppid() != mosb) return 2;
  // Its name and its children's, until the solver executes (executed from memory, the program
  // would be named after its descriptor's number).
  ::prctl(PR_SET_NAME, "mosb-forkserver", 0, 0, 0);
  while (true) {
    Request request;
    if (!receive(request)) return 0;
    ParkReply reply;
    reply.pid = park(request, mosb);
    reply.error = reply.pid < 0 ? errno : 0;
    for (std::size_t i = 0; i < request.count; ++i) ::close(request.fds[i]);
    if (::send(kSocket, &reply, sizeof reply, MSG_NOSIGNAL) != sizeof reply) return 0;
  }
}
