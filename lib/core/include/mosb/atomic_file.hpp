// One way to write a file so that its name never shows a partial file: every mosb writer (the
// .mosb writer, in-place query-set edits, DIMACS export, suite MANIFESTs, exposure grids) goes
// through AtomicFile.
//
// Guarantees:
//  * The data is written to a temporary `.NAME.tmp-PID-XXXXXX` (PID of the writing process,
//    XXXXXX random) in the directory the final file goes to, created with O_CREAT|O_EXCL|
//    O_NOFOLLOW, so an existing file or symlink at that name is never opened or followed.
//  * commit() fsyncs the data and renames the temporary onto the target: a reader sees the old
//    file or the complete new one, never a mixture. Until then the target is untouched.
//  * The temporary is removed by the destructor of an uncommitted AtomicFile, so on every error
//    path (a write error such as EFBIG or ENOSPC, a failed fsync or rename, an exception of the
//    caller); and, once remove_temporaries_on_signals() is installed, on SIGINT, SIGTERM, SIGHUP
//    and SIGQUIT.
//  * Only kill -9 (or a crash, or power loss) can leave a temporary behind. The next AtomicFile
//    for the same target removes temporaries of that target whose PID is no longer alive (in this
//    PID namespace; temporaries of live processes are kept) and reports each removal to the
//    handler given to set_stale_temporary_handler().
//  * Existing::replace (new outputs): the new file's mode is 0666 & ~umask, like any new file; an
//    existing target, or a symlink at the target's name, is replaced.
//  * Existing::rewrite_in_place (editing a file): the target must exist; a symlink is followed and
//    its final target rewritten (the symlink stays); the mode (and, where permitted, the owner and
//    group) is kept; a target without any write permission bit, or not writable by this process,
//    is refused; a target with several hard links is refused, since renaming a new file over one
//    name would split it from the others.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <string_view>
#include <vector>

namespace mosb {

class AtomicFile {
 public:
  enum class Existing { replace, rewrite_in_place };

  // Creates the temporary; throws mosb::Error naming `target` when it cannot.
  explicit AtomicFile(std::filesystem::path target, Existing existing = Existing::replace);
  ~AtomicFile();  // removes the temporary unless committed
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;

  // Appends all of `size` bytes (retrying short writes); a failure throws mosb::Error naming the
  // target, e.g. "out.mosb: write failed: File too large". Each 8 MiB appended is handed to the
  // disk at once (Linux: sync_file_range), so that commit()'s fsync has little left to wait for.
  void write(const void* data, std::size_t size);
  void write(std::string_view text) { write(text.data(), text.size()); }
  // Writes at `offset` without moving the append position.
  void write_at(const void* data, std::size_t size, std::uint64_t offset);
  // fsync, close, rename onto the target. Throws mosb::Error (and keeps the target) on failure.
  void commit();

  // The file that is replaced at commit (for an in-place rewrite through a symlink: its target).
  const std::filesystem::path& target() const { return target_; }
  const std::filesystem::path& temporary() const { return temporary_; }

 private:
  [[noreturn]] void fail(const std::string& what) const;

  std::filesystem::path target_;
  std::filesystem::path temporary_;
  int fd_ = -1;
  std::uint64_t appended_ = 0;           // bytes appended by write()
  std::uint64_t writeback_started_ = 0;  // of those, bytes whose writeback to disk has begun
  int slot_ = -1;                        // in the signal registry, or -1
  bool committed_ = false;
};

// Writes `content` as the whole of `target` through an AtomicFile (Existing::replace): the target
// shows its old content or all of the new. Throws mosb::Error naming the target.
void write_file_atomically(const std::filesystem::path& target, std::string_view content);

// A file of a set written all or nothing: its name and its whole content (the caller keeps it).
struct FileContent {
  std::filesystem::path path;
  std::string_view content;
};

// Writes `files` all or nothing (mosb report's page, tables and figures). Each of `directories`
// is made when missing, with its parents; every other file's directory must exist. First every
// destination is checked, before anything is touched: a directory to make is a directory or can
// be made (its nearest existing ancestor is a directory), no file names an existing directory or
// is named twice, each file's directory exists or is one to make. Then the directories are made,
// each file is written to its temporary (AtomicFile), and only once every file is written are the
// temporaries renamed onto their names, in order. On an error before that nothing is left behind,
// no temporary and no directory made here, and the mosb::Error names the file or directory. (Only
// a rename that fails once others succeeded, the destination having changed meanwhile, leaves the
// files renamed before it.)
void write_files_atomically(const std::vector<std::filesystem::path>& directories,
                            const std::vector<FileContent>& files);

// Called (from the writing thread, one call at a time) with each stale temporary that was
// removed; the library prints nothing itself. An empty function removes them silently (the
// default).
void set_stale_temporary_handler(std::function<void(const std::filesystem::path&)> handler);

// Installs handlers for SIGINT, SIGTERM, SIGHUP and SIGQUIT that unlink every live temporary and
// then re-raise the signal with its default action (so the exit status is the usual one). A signal
// that is ignored when this is called stays ignored. For programs: a library embedding mosb keeps
// its own handlers unless it calls this.
void remove_temporaries_on_signals();

// True when no process `pid` exists (in this PID namespace; one that exists but is not ours to
// signal counts as alive): how a leftover named after the PID of its writer is known to be
// abandoned (the stale temporaries above; a store's staging directories).
bool process_has_ended(long pid);

// Throws mosb::Error when `output` exists and is the same file (device and inode, after following
// symlinks) as one of `inputs`: writing it would destroy that input. Empty paths are skipped.
void check_output_is_not_input(const std::filesystem::path& output,
                               const std::vector<std::filesystem::path>& inputs);

}  // namespace mosb
