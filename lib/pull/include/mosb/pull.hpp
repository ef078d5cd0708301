// `mosb store pull`: copies a published store (a directory of mosb files and its MANIFEST, served
// by any static HTTP(S) server, or a local directory) into a local store, so that nothing
// unverified ever lands where a solver maps it (spec/MANIFEST.md, "Publishing and pulling").
//
// Its own component (mosb::pull) because it is the only part of mosb that needs libcurl: the
// store, the C ABI and the reader link no network library.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <vector>

#include "mosb/enum_names.hpp"
#include "mosb/manifest.hpp"
#include "mosb/pack.hpp"
#include "mosb/progress.hpp"

namespace mosb {

enum class PullStatus {
  fetched,  // transferred, verified, placed and listed by this pull
  present,  // the store already lists it with the published SHA-256: not transferred
  refused,  // not placed: `reason` says why
  planned,  // dry run: would be fetched
};
inline constexpr auto kPullStatusNames = enum_names<PullStatus>({
    {PullStatus::fetched, "fetched"},
    {PullStatus::present, "present"},
    {PullStatus::refused, "refused"},
    {PullStatus::planned, "planned"},
});

struct PulledEntry {
  ManifestEntry entry;  // as the published MANIFEST lists it
  PullStatus status = PullStatus::planned;
  Message reason;  // refused: one line, what differs or what failed (message_text spells it)
  std::uint64_t received = 0;  // bytes received for it by this pull (retries included)
  // The offset at which a partial file left by an earlier transfer was continued, or 0 (when the
  // transfer started from zero, or the server answered the range with other bytes).
  std::uint64_t resumed_from = 0;
  // "", or what the server answered a request to continue at some byte with, when that made the
  // transfer start again from byte 0 (the whole file, HTTP 416, another range): one line.
  std::string restarted;
};

struct PullOptions {
  // fnmatch(3) patterns; when a list is not empty an entry is pulled only if one of them matches
  // (its benchmark, one of its views, its file name). Empty lists: every entry.
  std::vector<std::string> benchmarks;
  std::vector<std::string> views;
  std::vector<std::string> files;
  // Solution files (references) too, each placed once its instance is: after every instance.
  bool references = true;
  // Not empty: only the solution files bound to instances of these content digests, and those
  // instances (a solution file is checked against its instance): a published store's references
  // of one's own instances (`eval --reference URL`).
  std::set<std::string> references_of;
  unsigned jobs = 4;  // transfers at once
  // Unpack each packed entry into the store's cache once it is listed (Store::unpack), so that
  // Store::instance maps it at once.
  bool unpack = false;
  bool dry_run = false;  // fetch the MANIFEST only: say what would be fetched, write nothing
  // A transfer that receives no byte for this long is dropped and retried (so is a connection
  // that takes this long to open).
  unsigned stall_timeout_seconds = 60;
  // Transfers of one file before it is given up, on transient failures only (connection reset,
  // timeout, HTTP 5xx, 408, 429). A transfer that moved a resumable file forward does not count.
  unsigned attempts = 6;
  double first_backoff_seconds = 0.5;  // before the first retry; doubled each time, at most 30 s
  // The working memory of each entry's check (Store::AddOptions::check_memory).
  std::uint64_t check_memory = StreamingVerifyOptions{}.memory;
  // The most disk each entry's check may spill (Store::AddOptions::check_disk); nullopt:
  // default_check_disk(the entry's size, check_memory).
  std::optional<std::uint64_t> check_disk;
  Progress progress;  // stage "pull": bytes in the staging area out of the bytes to fetch
  // Called as each selected entry is settled (fetched, present or refused), one call at a time,
  // with how many are settled and how many were selected. Not called by a dry run.
  std::function<void(const PulledEntry& entry, std::size_t settled, std::size_t selected)> settled;
};

struct PullResult {
  std::string manifest_url;          // where the MANIFEST was read
  std::vector<PulledEntry> entries;  // the selected entries, in MANIFEST order
  std::uint64_t bytes = 0;           // bytes received, MANIFEST included
  double seconds = 0;
  bool ok() const;  // nothing refused
};

// Pulls the store published at `url` (http://, https://, file:// or a directory path; with or
// without a trailing slash; the MANIFEST at URL/MANIFEST, each entry at URL/FILE) into the store
// `store`, created when it has no MANIFEST.
//
// The published MANIFEST is read first and must be a valid JSON Lines manifest listing no name
// the store keeps for itself; otherwise mosb::Error is thrown before any entry is fetched and
// nothing is written. Each selected entry the store does not already list with its SHA-256 is
// streamed into DIR/.staging/pull/FILE/ while its SHA-256 is computed; its size and SHA-256 must
// be the listed ones, then Store::add checks it (content digest, verify --level full, packed
// files decoded) and places and lists it under the store's writer lock. A partial file left there
// (a dropped connection, Ctrl-C, kill -9) is continued with an HTTP Range request validated by
// If-Range. An entry that fails is refused (PullStatus::refused) and the others go on.
PullResult pull(const std::filesystem::path& store, std::string_view url,
                const PullOptions& options);

// True for what pull() fetches from a server (http://, https://, file://), not a directory path.
bool is_store_url(std::string_view source);

// Where the store published at `url` is pulled to be read, not kept: $MOSB_STORE_CACHE/KEY, else
// $XDG_CACHE_HOME/mosb/stores/KEY, else $HOME/.cache/mosb/stores/KEY, KEY the first 16 hex digits
// of the SHA-256 of the URL without its trailing slashes. What `eval` and `report` pull a
// published store's references into (`--reference URL`).
std::filesystem::path store_cache(std::string_view url);

}  // namespace mosb
