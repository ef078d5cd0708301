// The processes of one query between their fork and the solver's exec (spec/RUN.md §4): the
// messages mosb, the fork server and these processes exchange, and the code the processes run.
// Compiled into lib/run and into the fork server (fork_server.cpp), which forks them on mosb's
// request. Everything a forked process calls here is async-signal-safe.
#pragma once

#include <sys/resource.h>
#include <sys/types.h>

#include <cstddef>
#include <cstdint>
#include <string>

namespace mosb::run_internal {

// What the child reports through its error pipe when it cannot execute.
struct ChildError {
  // 1: joining the cgroup, 2: execve, 3: opening /dev/null, stdout or stderr, 4: creating the PID
  // namespace, 5: forking the launcher or the solver, 6: sealing the query
  int stage = 0;
  int error = 0;
};

// The fixed part of the command a parked child receives; `size` bytes follow: the executable,
// the stdout path, the stderr path and then every argument, each ending in NUL. When
// `executable_fd` is 1, the executable's descriptor comes with the header (SCM_RIGHTS) and is
// executed (fexecve) instead of the path.
struct LaunchHeader {
  std::uint32_t size = 0;
  std::int32_t cpu = -1;
  std::uint64_t rlimit_as = 0;
  std::int32_t executable_fd = 0;
};

// The most a command may hold: bytes after the header, and words (the three paths and argv).
inline constexpr std::size_t kLaunchBytes = std::size_t{256} * 1024;
inline constexpr std::size_t kLaunchWords = std::size_t{16} * 1024;

// What the launcher tells mosb when the solver has ended (on the command socket).
// It is sent once nothing of the query is left, so mosb ends the query on it and reaps the
// launcher's chain later, off the query's critical path.
struct LauncherReport {
  std::int32_t status = 0;      // the solver's wait status
  std::int32_t leftovers = 0;   // 1: descendants outlived the solver and were killed
  std::int64_t max_rss_kb = 0;  // the solver's ru_maxrss (with its waited-for descendants)
  // User + system time of every process the launcher reaped: the solver and what it left.
  std::int64_t cpu_microseconds = 0;
  // When the report was sent, on CLOCK_MONOTONIC (mosb's steady clock): the end of the query's
  // wall time, whenever mosb gets to read it.
  std::int64_t sent_nanoseconds = 0;
};

// What a parked child needs to seal its query (spec/RUN.md §4.1), made before the fork: the child
// of a threaded process must not allocate.
struct SealSetup {
  bool on = false;
  bool user_namespace = false;    // not root: a user namespace that maps the user alone
  std::string queries_directory;  // where the query directories are made
  std::string uid_map, gid_map;   // "ID ID 1" for the user namespace
  int queries_fd = -1;            // in the child: the queries directory, before anything is hidden
  // As root: the runner's network namespace (loopback up), joined instead of making one per query.
  int network_fd = -1;

  SealSetup(bool sealed, std::string directory, int network);
};

// mosb's request to the fork server for one parked child, on a SOCK_SEQPACKET socket: this header,
// then `directory_size` bytes of the queries directory (SealSetup). The descriptors come with it
// (SCM_RIGHTS), in this order: the child's end of the command socket, the write end of its error
// pipe, then the memory group's cgroup.procs when `has_procs` and the network namespace when
// `has_network`.
struct ParkRequest {
  std::int32_t pid_namespace = 0;  // 1: Isolation::pid_namespace, 0: subreaper
  std::int32_t sealed = 0;
  std::int32_t has_procs = 0;
  std::int32_t has_network = 0;
  std::uint32_t directory_size = 0;
};
inline constexpr std::size_t kMaxDirectory = 4096;
// The fork server's answer: the parked child's pid (mosb's child), or -1 and the errno.
struct ParkReply {
  std::int32_t pid = -1;
  std::int32_t error = 0;
};

// The open-file limit mosb was started with, which every program it starts gets back (execute):
// mosb itself raises its soft limit to the hard one, since each job holds some thirty descriptors
// (the sockets, pipes and memory-group files of the queries forked ahead, running and ending).
// The fork server gets it on its command line.
extern rlimit started_file_limit;

// `size` bytes from the socket `fd` (recv with `flags`: MSG_DONTWAIT for bytes already there), or
// false at the end of the stream or an error.
bool read_exactly(int fd, void* data, std::size_t size, int flags = 0);
// `count` bytes to the socket `fd`, or false.
bool write_exactly(int fd, const void* data, std::size_t count);

// The most descriptors one message carries (a park request's).
inline constexpr std::size_t kMaxDescriptors = 4;
// `size` bytes to `socket`, `count` (at most kMaxDescriptors) descriptors with them (SCM_RIGHTS);
// false, errno set, when they cannot be sent.
bool send_with_descriptors(int socket, const void* data, std::size_t size, const int* fds,
                           std::size_t count);
// One recvmsg of up to `size` bytes from `socket`, and the descriptors that came with them, made
// close-on-exec, into `fds` (at most `count`, which becomes how many came; the rest are closed):
// recvmsg's result.
ssize_t receive_with_descriptors(int socket, void* data, std::size_t size, int* fds,
                                 std::size_t& count);

// In a forked child: reports `stage` and errno on `error_fd` (when the child has one) and exits
// with 127, a shell's status for a command it cannot run.
[[noreturn]] void report_and_exit(int error_fd, int stage);

// In a forked child, once it is prepared: stdout and stderr become `output` and `errors`, and the
// program replaces the child (async-signal-safe calls only). Every program lib/run starts is
// executed here; one that cannot be is reported as stage 2.
[[noreturn]] void execute(const char* executable, char* const argv[], int output, int errors,
                          int error_fd, int executable_fd = -1);

// The network namespace's loopback interface, up: a solver (or its helper processes) may talk to
// itself, to nothing else.
bool loopback_up();

// In the parked child, ahead of its query: the mount and network namespaces every process of the
// query inherits, with every mount read-only (and nosuid) and a private /dev/shm. The query's own
// directory is made writable once the command names it. False, errno set, when the kernel
// refuses.
bool seal_namespaces(SealSetup& s);

// The parked child of one query, started by the fork server: leaves mosb's process group, joins
// its memory group (`procs_fd` >= 0), seals the query, and starts the query's launcher (in a new
// PID namespace when `pid_namespace`, else as a subreaper), which forks the solver's process; the
// group join, which takes milliseconds under cgroup v1 on a loaded machine, and these forks happen
// while the previous solver still runs. `mosb` is the pid of its parent.
[[noreturn]] void parked_child(int command_fd, int error_fd, int procs_fd, pid_t mosb,
                               bool pid_namespace, SealSetup& seal);

}  // namespace mosb::run_internal
