#include "mosb/pull.hpp"

#include <curl/curl.h>
#include <fcntl.h>
#include <fnmatch.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <deque>
#include <memory>
#include <mutex>
#include <nlohmann/json.hpp>
#include <optional>
#include <thread>

#include "mosb/atomic_file.hpp"
#include "mosb/error.hpp"
#include "mosb/internal/parallel.hpp"
#include "mosb/internal/read_file.hpp"
#include "mosb/sha256.hpp"
#include "mosb/store.hpp"
#include "mosb/version.hpp"

namespace mosb {

bool PullResult::ok() const {
  return std::none_of(entries.begin(), entries.end(),
                      [](const PulledEntry& e) { return e.status == PullStatus::refused; });
}

namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

constexpr std::size_t kManifestLimit = std::size_t{256} << 20;
constexpr std::size_t kChunk = std::size_t{1} << 20;
constexpr std::string_view kPullDirectory = "pull";      // in DIR/.staging
constexpr std::string_view kValidators = ".validators";  // beside a partial file
constexpr double kMaxBackoff = 30;
constexpr double kMaxRetryAfter = 120;

bool starts_with_nocase(std::string_view text, std::string_view prefix) {
  return text.size() >= prefix.size() &&
         std::equal(prefix.begin(), prefix.end(), text.begin(), [](char a, char b) {
           return std::tolower(static_cast<unsigned char>(a)) ==
                  std::tolower(static_cast<unsigned char>(b));
         });
}

std::string percent_decode(std::string_view text) {
  std::string out;
  for (std::size_t i = 0; i < text.size(); ++i) {
    if (text[i] == '%' && i + 2 < text.size() &&
        std::isxdigit(static_cast<unsigned char>(text[i + 1])) &&
        std::isxdigit(static_cast<unsigned char>(text[i + 2]))) {
      out += static_cast<char>(std::stoi(std::string(text.substr(i + 1, 2)), nullptr, 16));
      i += 2;
    } else {
      out += text[i];
    }
  }
  return out;
}

// RFC 3986 unreserved characters stay, every other byte of a name becomes %XX.
std::string percent_encode(std::string_view name) {
  static constexpr char kDigits[] = "0123456789ABCDEF";
  std::string out;
  for (const char c : name) {
    const auto u = static_cast<unsigned char>(c);
    if (std::isalnum(u) || c == '-' || c == '.' || c == '_' || c == '~') {
      out += c;
    } else {
      out += '%';
      out += kDigits[u >> 4];
      out += kDigits[u & 0xF];
    }
  }
  return out;
}

// Where a published store is: an HTTP(S) base URL or a local directory.
struct Location {
  bool http = false;
  std::string base;  // http: the URL without trailing '/'
  fs::path directory;

  std::string url_of(std::string_view name) const {
    return http ? base + "/" + percent_encode(name) : (directory / name).string();
  }
};

Location locate(std::string_view url) {
  Location where;
  if (starts_with_nocase(url, "http://") || starts_with_nocase(url, "https://")) {
    where.http = true;
    where.base = std::string(url);
    while (where.base.ends_with('/')) where.base.pop_back();
  } else if (starts_with_nocase(url, "file://")) {
    const auto path = url.substr(7);
    if (!path.starts_with('/'))
      throw Error(std::string(url) + ": a file URL names an absolute path (file:///DIR)");
    where.directory = percent_decode(path);
  } else if (url.find("://") != std::string_view::npos) {
    throw Error(std::string(url) +
                ": not a place mosb pulls from (http://, https://, file:// or a directory)");
  } else {
    where.directory = std::string(url);
  }
  return where;
}

// ---------------------------------------------------------------------------------------------
// HTTP through libcurl

void start_curl() {
  static const CURLcode started = curl_global_init(CURL_GLOBAL_DEFAULT);
  if (started != CURLE_OK)
    throw Error(std::string("libcurl cannot start: ") + curl_easy_strerror(started));
}

struct Response {
  long status = 0;
  std::string etag;
  std::string last_modified;
  std::string content_range;
  double retry_after = -1;  // seconds, -1 when absent
};

std::string_view trimmed(std::string_view text) {
  while (!text.empty() && std::isspace(static_cast<unsigned char>(text.front())))
    text.remove_prefix(1);
  while (!text.empty() && std::isspace(static_cast<unsigned char>(text.back())))
    text.remove_suffix(1);
  return text;
}

void read_header(Response& response, std::string_view text) {
  const std::string_view line = trimmed(text);
  if (line.starts_with("HTTP/")) {
    response = {};  // a new response: after a redirect, or a 100 Continue
    return;
  }
  const auto colon = line.find(':');
  if (colon == std::string_view::npos) return;
  const auto name = line.substr(0, colon);
  const auto value = std::string(trimmed(line.substr(colon + 1)));
  if (starts_with_nocase(name, "etag") && name.size() == 4) {
    response.etag = value;
  } else if (starts_with_nocase(name, "last-modified") && name.size() == 13) {
    response.last_modified = value;
  } else if (starts_with_nocase(name, "content-range") && name.size() == 13) {
    response.content_range = value;
  } else if (starts_with_nocase(name, "retry-after") && name.size() == 11) {
    if (!value.empty() && value.find_first_not_of("0123456789") == std::string::npos) {
      response.retry_after = std::stod(value);
    } else if (const auto when = curl_getdate(value.c_str(), nullptr); when >= 0) {
      response.retry_after = std::max(0.0, std::difftime(when, std::time(nullptr)));
    }
  }
}

// libcurl's callbacks are C: nothing may be thrown through them.
std::size_t on_header(char* data, std::size_t size, std::size_t count, void* user) try {
  read_header(*static_cast<Response*>(user), {data, size * count});
  return size * count;
} catch (...) {
  return 0;
}

// What a transfer's body goes to.
class Sink {
 public:
  virtual ~Sink() = default;
  // At the first byte of a 2xx response's body (or its end, when it has none); false aborts.
  virtual bool begin(long status, const Response& response) = 0;
  // False aborts the transfer.
  virtual bool data(const char* bytes, std::size_t size) = 0;
};

// One libcurl handle per thread, reused for every transfer it makes (connections are kept).
class Http {
 public:
  explicit Http(unsigned stall_timeout) : curl_(curl_easy_init()) {
    if (curl_ == nullptr) throw Error("libcurl cannot make a transfer handle");
    const long stall = std::max(1U, stall_timeout);
    curl_easy_setopt(curl_, CURLOPT_NOSIGNAL, 1L);
    curl_easy_setopt(curl_, CURLOPT_FOLLOWLOCATION, 1L);
    curl_easy_setopt(curl_, CURLOPT_MAXREDIRS, 10L);
    // A published store is fetched over HTTP(S) only: a redirect to file:// or elsewhere is
    // refused.
    curl_easy_setopt(curl_, CURLOPT_PROTOCOLS_STR, "http,https");
    curl_easy_setopt(curl_, CURLOPT_REDIR_PROTOCOLS_STR, "http,https");
    curl_easy_setopt(curl_, CURLOPT_USERAGENT, ("mosb/" + std::string(version())).c_str());
    curl_easy_setopt(curl_, CURLOPT_CONNECTTIMEOUT, stall);
    curl_easy_setopt(curl_, CURLOPT_LOW_SPEED_LIMIT, 1L);  // fewer than 1 byte/s for `stall` s
    curl_easy_setopt(curl_, CURLOPT_LOW_SPEED_TIME, stall);
    curl_easy_setopt(curl_, CURLOPT_BUFFERSIZE, 512L * 1024);
    curl_easy_setopt(curl_, CURLOPT_ERRORBUFFER, error_);
    curl_easy_setopt(curl_, CURLOPT_HEADERFUNCTION, &on_header);
    curl_easy_setopt(curl_, CURLOPT_WRITEFUNCTION, &on_data);
  }
  ~Http() { curl_easy_cleanup(curl_); }
  Http(const Http&) = delete;
  Http& operator=(const Http&) = delete;

  struct Result {
    CURLcode code = CURLE_OK;
    long status = 0;
    Response response;
    std::string error;  // libcurl's words, when code is not CURLE_OK
  };

  // GET `url`, from byte `from` on (a Range request, with If-Range `if_range` when not empty).
  Result get(const std::string& url, std::uint64_t from, const std::string& if_range, Sink& sink) {
    Transfer t{this, &sink, {}, false};
    error_[0] = '\0';
    curl_easy_setopt(curl_, CURLOPT_URL, url.c_str());
    curl_easy_setopt(curl_, CURLOPT_HEADERDATA, &t.response);
    curl_easy_setopt(curl_, CURLOPT_WRITEDATA, &t);
    const auto range = std::to_string(from) + "-";
    curl_easy_setopt(curl_, CURLOPT_RANGE, from > 0 ? range.c_str() : nullptr);
    curl_slist* headers = nullptr;
    if (from > 0 && !if_range.empty())
      headers = curl_slist_append(headers, ("If-Range: " + if_range).c_str());
    curl_easy_setopt(curl_, CURLOPT_HTTPHEADER, headers);
    Result r;
    r.code = curl_easy_perform(curl_);
    curl_easy_setopt(curl_, CURLOPT_HTTPHEADER, nullptr);
    curl_slist_free_all(headers);
    curl_easy_getinfo(curl_, CURLINFO_RESPONSE_CODE, &r.status);
    r.response = t.response;
    if (r.code == CURLE_OK && !t.began && r.status / 100 == 2 && !sink.begin(r.status, r.response))
      r.code = CURLE_WRITE_ERROR;
    if (r.code != CURLE_OK)
      r.error = error_[0] != '\0' ? std::string(error_) : curl_easy_strerror(r.code);
    return r;
  }

 private:
  struct Transfer {
    Http* http;
    Sink* sink;
    Response response;
    bool began;
  };

  static std::size_t on_data(char* data, std::size_t size, std::size_t count, void* user) try {
    auto& t = *static_cast<Transfer*>(user);
    const std::size_t bytes = size * count;
    long status = 0;
    curl_easy_getinfo(t.http->curl_, CURLINFO_RESPONSE_CODE, &status);
    if (status / 100 != 2) return bytes;  // an error page: the status says it all
    if (!t.began) {
      t.began = true;
      t.response.status = status;
      if (!t.sink->begin(status, t.response)) return 0;
    }
    return t.sink->data(data, bytes) ? bytes : 0;
  } catch (...) {
    return 0;  // libcurl's callbacks are C: nothing may be thrown through them
  }

  CURL* curl_;
  char error_[CURL_ERROR_SIZE] = {};
};

enum class Verdict { done, transient, permanent };

// What a finished transfer means: done (a 2xx response received in full), worth another try, or
// not. `why` is one line; `wait` the server's Retry-After when it sent one.
Verdict judge(const Http::Result& r, std::string& why, double& wait) {
  wait = r.response.retry_after;
  if (r.code == CURLE_OK) {
    if (r.status / 100 == 2) return Verdict::done;
    why = "HTTP " + std::to_string(r.status);
    return r.status >= 500 || r.status == 408 || r.status == 429 ? Verdict::transient
                                                                 : Verdict::permanent;
  }
  why = r.error;
  switch (r.code) {
    case CURLE_COULDNT_CONNECT:
    case CURLE_OPERATION_TIMEDOUT:
    case CURLE_PARTIAL_FILE:
    case CURLE_RECV_ERROR:
    case CURLE_SEND_ERROR:
    case CURLE_GOT_NOTHING:
    case CURLE_HTTP2:
    case CURLE_HTTP2_STREAM:
      return Verdict::transient;
    default:
      return Verdict::permanent;
  }
}

double backoff(const PullOptions& options, unsigned retry, double retry_after) {
  double wait = std::min(kMaxBackoff, options.first_backoff_seconds * std::pow(2.0, retry));
  if (retry_after >= 0) wait = std::min(kMaxRetryAfter, retry_after);
  return wait;
}

void sleep_seconds(double seconds) {
  std::this_thread::sleep_for(std::chrono::duration<double>(seconds));
}

class StringSink : public Sink {
 public:
  explicit StringSink(std::string& text) : text_(text) {}
  bool begin(long, const Response&) override {
    text_.clear();
    return true;
  }
  bool data(const char* bytes, std::size_t size) override {
    if (text_.size() + size > kManifestLimit) return false;
    text_.append(bytes, size);
    return true;
  }

 private:
  std::string& text_;
};

// A regular file opened for reading (O_NONBLOCK: a FIFO does not block the open).
int open_regular(const fs::path& path) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) throw Error(ErrorCode::io, path.string() + ": cannot open: " + std::strerror(errno));
  struct stat st {};
  if (::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
    ::close(fd);
    throw Error(ErrorCode::io, path.string() + ": not a regular file");
  }
  return fd;
}

struct Fd {
  int fd = -1;
  ~Fd() {
    if (fd >= 0) ::close(fd);
  }
};

// Calls consume(data, size) per chunk of the whole file; false from it stops the read (and this
// returns false).
template <class F>
bool read_file(int fd, const fs::path& path, F consume) {
  if (::lseek(fd, 0, SEEK_SET) < 0)
    throw Error(ErrorCode::io, path.string() + ": cannot read: " + std::strerror(errno));
  std::vector<char> buffer(kChunk);
  return read_chunks(fd, path, buffer, consume);
}

std::string fetch_manifest(const Location& where, const PullOptions& options,
                           std::uint64_t& bytes) {
  const auto url = where.url_of(kManifestName);
  std::string text;
  if (!where.http) {
    Fd in{open_regular(url)};
    read_file(in.fd, url, [&](const char* data, std::size_t size) {
      if (text.size() + size > kManifestLimit)
        throw Error(url + ": larger than " + std::to_string(kManifestLimit >> 20) +
                    " MiB; not a MANIFEST");
      text.append(data, size);
      return true;
    });
    bytes += text.size();
    return text;
  }
  Http http(options.stall_timeout_seconds);
  StringSink sink(text);
  for (unsigned attempt = 1;; ++attempt) {
    const auto r = http.get(url, 0, "", sink);
    std::string why;
    double wait = -1;
    const auto verdict = judge(r, why, wait);
    if (verdict == Verdict::done) break;
    if (r.code == CURLE_WRITE_ERROR)
      throw Error(url + ": larger than " + std::to_string(kManifestLimit >> 20) +
                  " MiB; not a MANIFEST");
    if (verdict == Verdict::permanent || attempt >= std::max(1U, options.attempts))
      throw Error(ErrorCode::io, url + ": " + why);
    sleep_seconds(backoff(options, attempt - 1, wait));
  }
  bytes += text.size();
  return text;
}

// ---------------------------------------------------------------------------------------------
// The staging area: DIR/.staging/pull/FILE/ holds FILE (the bytes received so far) and
// .validators (where they came from and the server's ETag and Last-Modified for them).

// Makes `path` as a directory of the store's own, refusing a symlink or anything else there.
void own_directory(const fs::path& path) {
  if (::mkdir(path.c_str(), 0777) == 0) return;
  const int error = errno;
  struct stat st {};
  if (error != EEXIST || ::lstat(path.c_str(), &st) != 0)
    throw Error(ErrorCode::io, path.string() + ": cannot create: " + std::strerror(error));
  if (S_ISLNK(st.st_mode))
    throw Error(path.string() + ": is a symbolic link, which the store did not make; not followed");
  if (!S_ISDIR(st.st_mode))
    throw Error(path.string() + ": is not a directory; the store keeps its own files there");
}

// The exclusive use of one entry's staging directory: concurrent pulls of one store take turns
// per entry (flock on the directory), and the second finds the entry listed by the first.
class EntryLock {
 public:
  explicit EntryLock(const fs::path& store, const std::string& file)
      : parent_(store / kStagingDirectory / kPullDirectory), path_(parent_ / file) {
    for (int attempt = 0;; ++attempt) {
      try {
        // A store add's sweep may remove an empty .staging at any moment.
        own_directory(store / kStagingDirectory);
        own_directory(parent_);
        own_directory(path_);
      } catch (const Error&) {
        if (attempt < 3) continue;
        throw;
      }
      fd_ = ::open(path_.c_str(), O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
      if (fd_ < 0) {
        if (errno == ENOENT && attempt < 100) continue;
        throw Error(ErrorCode::io, path_.string() + ": cannot open: " + std::strerror(errno));
      }
      while (::flock(fd_, LOCK_EX) != 0)
        if (errno != EINTR)
          throw Error(ErrorCode::io, path_.string() + ": cannot lock: " + std::strerror(errno));
      // The holder before us may have removed the directory when it was done with it.
      struct stat held {
      }, there{};
      if (::fstat(fd_, &held) == 0 && ::lstat(path_.c_str(), &there) == 0 &&
          held.st_dev == there.st_dev && held.st_ino == there.st_ino)
        return;
      ::close(fd_);
      fd_ = -1;
    }
  }
  ~EntryLock() {
    if (remove_) {
      std::error_code ec;
      fs::remove_all(path_, ec);
      ::rmdir(parent_.c_str());  // fails, harmlessly, while another entry is staged
    }
    if (fd_ >= 0) ::close(fd_);
  }
  EntryLock(const EntryLock&) = delete;
  EntryLock& operator=(const EntryLock&) = delete;

  const fs::path& path() const { return path_; }
  int fd() const { return fd_; }  // the directory, open and locked
  void remove_when_done() { remove_ = true; }

 private:
  fs::path parent_;
  fs::path path_;
  int fd_ = -1;
  bool remove_ = false;
};

struct Validators {
  std::string url;
  std::string sha256;
  std::uint64_t size = 0;
  std::string etag;
  std::string last_modified;

  // What If-Range may carry: a strong ETag, else Last-Modified; "" when the server sent neither.
  std::string if_range() const {
    if (!etag.empty() && !etag.starts_with("W/")) return etag;
    return last_modified;
  }
};

std::optional<Validators> read_validators(const fs::path& path) {
  std::error_code ec;
  if (!fs::is_regular_file(fs::symlink_status(path, ec))) return std::nullopt;
  try {
    std::string text;
    Fd in{open_regular(path)};
    read_file(in.fd, path, [&](const char* data, std::size_t size) {
      text.append(data, size);
      return text.size() < 65536;
    });
    const auto json = nlohmann::json::parse(text);
    return Validators{json.at("url").get<std::string>(), json.at("sha256").get<std::string>(),
                      json.at("size").get<std::uint64_t>(), json.at("etag").get<std::string>(),
                      json.at("last_modified").get<std::string>()};
  } catch (const std::exception&) {
    return std::nullopt;  // unreadable: the partial file is not trusted, the transfer restarts
  }
}

void write_validators(const fs::path& path, const Validators& v) {
  const nlohmann::json json{{"url", v.url},
                            {"sha256", v.sha256},
                            {"size", v.size},
                            {"etag", v.etag},
                            {"last_modified", v.last_modified}};
  write_file_atomically(path, json.dump() + "\n");
}

// The checks of received entries, at most one per core at once (they are CPU-bound; more would
// only interleave), each with a workspace kept from one check to the next.
class CheckSlots {
 public:
  explicit CheckSlots(unsigned count) : workspaces_(std::max(1U, count)) {
    for (auto& w : workspaces_) idle_.push_back(&w);
  }
  // Runs f(workspace) in a free slot, waiting for one.
  template <class F>
  void run(F f) {
    VerifyWorkspace* workspace = nullptr;
    {
      std::unique_lock lock(mutex_);
      freed_.wait(lock, [&] { return !idle_.empty(); });
      workspace = idle_.back();
      idle_.pop_back();
    }
    auto give_back = [&] {
      {
        const std::lock_guard lock(mutex_);
        idle_.push_back(workspace);
      }
      freed_.notify_one();
    };
    try {
      f(*workspace);
    } catch (...) {
      give_back();
      throw;
    }
    give_back();
  }

 private:
  std::deque<VerifyWorkspace> workspaces_;  // not movable: a deque makes them in place
  std::vector<VerifyWorkspace*> idle_;
  std::mutex mutex_;
  std::condition_variable freed_;
};

// The pull's shared state: options, progress, where things are.
struct Puller {
  Puller(fs::path directory, Location location, const PullOptions& pull_options)
      : store(std::move(directory)), where(std::move(location)), options(pull_options) {}
  fs::path store;
  Location where;
  const PullOptions& options;
  std::atomic<std::uint64_t> staged{0};  // bytes in the staging files, for the progress bar
  std::atomic<std::uint64_t> received{0};
  std::uint64_t total = 0;
  std::mutex progress_mutex;
  CheckSlots checks{std::min(std::max(1U, options.jobs), thread_count(0))};

  std::size_t settled_count = 0;
  std::size_t selected = 0;

  void settled(const PulledEntry& entry) {
    if (!options.settled) return;
    std::lock_guard lock(progress_mutex);
    options.settled(entry, ++settled_count, selected);
  }

  void moved(std::int64_t delta) {
    const auto now = staged += static_cast<std::uint64_t>(delta);
    if (!options.progress) return;
    std::lock_guard lock(progress_mutex);
    // The last byte is reported once every entry is settled (placed or refused), at the end.
    report(options.progress, "pull", std::min(now, total - 1), total);
  }
};

// The file `name` in the entry's staging directory (open and locked as `directory`), opened for
// reading and writing: the one a pull left there (a regular file of one link) or a new one.
// Anything else found there (a symbolic link, a hard link, a directory, a FIFO) no pull made; as
// the directory is the pull's own, it is removed (a link, never what it leads to) and replaced.
int open_staging_file(int directory, const std::string& name, const fs::path& path) {
  const auto is_own = [](const struct stat& st) { return S_ISREG(st.st_mode) && st.st_nlink == 1; };
  std::string why = "it keeps changing";
  for (int attempt = 0; attempt < 3; ++attempt) {
    struct stat st {};
    if (::fstatat(directory, name.c_str(), &st, AT_SYMLINK_NOFOLLOW) == 0 && !is_own(st) &&
        ::unlinkat(directory, name.c_str(), S_ISDIR(st.st_mode) ? AT_REMOVEDIR : 0) != 0) {
      why = std::string("not a file a pull made, and it cannot be removed: ") +
            std::strerror(errno) + "; remove it and pull again";
      break;
    }
    const int fd = ::openat(directory, name.c_str(),
                            O_RDWR | O_CREAT | O_NOFOLLOW | O_NONBLOCK | O_CLOEXEC, 0666);
    if (fd < 0) {
      why = std::strerror(errno);
      if (errno == ELOOP || errno == EISDIR || errno == ENXIO) continue;  // replaced meanwhile
      break;
    }
    if (::fstat(fd, &st) == 0 && is_own(st)) return fd;
    ::close(fd);  // replaced between the look and the open: look again
  }
  throw Error(ErrorCode::io, path.string() + ": cannot open: " + why);
}

// The bytes of one entry as they arrive: appended to the staging file and hashed on the way.
class Receiver : public Sink {
 public:
  Receiver(Puller& puller, PulledEntry& pulled, const EntryLock& staging)
      : puller_(puller),
        pulled_(pulled),
        data_path_(staging.path() / pulled.entry.file),
        validators_path_(staging.path() / kValidators) {
    fd_.fd = open_staging_file(staging.fd(), pulled.entry.file, data_path_);
  }

  const fs::path& data_path() const { return data_path_; }
  std::uint64_t have() const { return have_; }
  std::string sha256() { return hash_.hex(); }
  bool too_long() const { return too_long_; }
  bool range_mismatch() const { return range_mismatch_; }
  const std::string& write_error() const { return write_error_; }

  // Takes over a partial file left by an earlier transfer of the same bytes from the same URL,
  // hashing what it holds; returns the If-Range validator to continue it with ("" when the
  // partial cannot be continued: it is then emptied).
  std::string resume(const std::string& url) {
    struct stat st {};
    if (::fstat(fd_.fd, &st) != 0) st.st_size = 0;
    const auto v = read_validators(validators_path_);
    const auto size = static_cast<std::uint64_t>(st.st_size);
    const auto& e = pulled_.entry;
    if (size == 0 || !v || v->url != url || v->sha256 != e.sha256 || v->size != e.size ||
        size > e.size || (v->if_range().empty() && size < e.size)) {
      restart();
      return "";
    }
    read_file(fd_.fd, data_path_, [&](const char* data, std::size_t n) {
      hash_.update(data, n);
      return true;
    });
    have_ = size;
    validators_ = *v;
    pulled_.resumed_from = size;
    puller_.moved(static_cast<std::int64_t>(size));
    return v->if_range();
  }

  // The server answered a request for the bytes from have() on with `answer` (the whole file, a
  // 416, another range): what is held goes, and the report says the transfer started again from
  // byte 0 rather than that it resumed.
  void restart_unresumed(const std::string& answer) {
    pulled_.restarted = "the server answered the range from byte " + std::to_string(have_) +
                        " with " + answer + ": fetched from byte 0";
    pulled_.resumed_from = 0;
    restart();
  }

  void restart() {
    if (::ftruncate(fd_.fd, 0) != 0)
      throw Error(ErrorCode::io,
                  data_path_.string() + ": cannot truncate: " + std::strerror(errno));
    (void)hash_.hex();  // starts the hash again
    puller_.moved(-static_cast<std::int64_t>(have_));
    have_ = 0;
  }

  // The validators of the bytes now held, "" when they cannot be continued.
  std::string if_range() const { return validators_.if_range(); }

  void set_url(const std::string& url) { url_ = url; }

  bool begin(long status, const Response& response) override {
    range_mismatch_ = false;
    if (status == 206) {
      // "bytes FIRST-LAST/SIZE": it must continue exactly where the partial file ends.
      const auto& range = response.content_range;
      const auto space = range.find(' ');
      const auto dash = range.find('-');
      if (space == std::string::npos || dash == std::string::npos ||
          range.substr(space + 1, dash - space - 1) != std::to_string(have_)) {
        range_mismatch_ = true;
        return false;
      }
      return true;
    }
    // The whole file (the server ignored Range, or If-Range said it changed): from zero.
    try {
      if (have_ > 0)  // a Range request
        restart_unresumed("HTTP " + std::to_string(status) + " and the whole file");
      else
        restart();
      validators_ = {url_, pulled_.entry.sha256, pulled_.entry.size, response.etag,
                     response.last_modified};
      write_validators(validators_path_, validators_);
    } catch (const Error& error) {
      write_error_ = error.message();
      return false;
    }
    return true;
  }

  bool data(const char* bytes, std::size_t size) override {
    if (have_ + size > pulled_.entry.size) {
      too_long_ = true;
      return false;
    }
    for (std::size_t done = 0; done < size;) {
      const ssize_t put =
          ::pwrite(fd_.fd, bytes + done, size - done, static_cast<off_t>(have_ + done));
      if (put < 0) {
        if (errno == EINTR) continue;
        write_error_ = data_path_.string() + ": cannot write: " + std::strerror(errno);
        return false;
      }
      done += static_cast<std::size_t>(put);
    }
    hash_.update(bytes, size);
    have_ += size;
    pulled_.received += size;
    puller_.received += size;
    puller_.moved(static_cast<std::int64_t>(size));
    return true;
  }

  void sync_and_close() {
    if (::fsync(fd_.fd) != 0)
      throw Error(ErrorCode::io, data_path_.string() + ": cannot sync: " + std::strerror(errno));
    ::close(fd_.fd);
    fd_.fd = -1;
  }

 private:
  Puller& puller_;
  PulledEntry& pulled_;
  fs::path data_path_;
  fs::path validators_path_;
  Fd fd_;
  Sha256 hash_;
  std::uint64_t have_ = 0;
  Validators validators_;
  std::string url_;
  bool too_long_ = false;
  bool range_mismatch_ = false;
  std::string write_error_;
};

std::string bytes_text(std::uint64_t n) {
  return std::to_string(n) + (n == 1 ? " byte" : " bytes");
}

// Transfers the entry into the receiver; "" when every byte arrived, else why not.
std::string transfer(Puller& p, Http* http, Receiver& r, const ManifestEntry& e) {
  const auto url = p.where.url_of(e.file);
  r.set_url(url);
  if (!p.where.http) {
    r.restart();  // a local copy is cheap: no partial file to trust
    Fd in{open_regular(url)};
    const bool complete = read_file(
        in.fd, url, [&](const char* data, std::size_t size) { return r.data(data, size); });
    if (!complete)
      return r.too_long() ? "more than the " + bytes_text(e.size) + " the MANIFEST says"
                          : r.write_error();
    return "";
  }
  std::string if_range = r.resume(url);
  if (r.have() == e.size) return "";  // complete already: a pull killed before placing it
  for (unsigned failures = 0;;) {
    const auto before = r.have();
    const auto result = http->get(url, r.have(), if_range, r);
    std::string why;
    double wait = -1;
    auto verdict = judge(result, why, wait);
    if (result.code == CURLE_WRITE_ERROR) {
      if (r.too_long()) return "more than the " + bytes_text(e.size) + " the MANIFEST says";
      if (!r.write_error().empty()) return r.write_error();
      if (r.range_mismatch()) {
        // A 206 for other bytes than asked: start again from zero.
        r.restart_unresumed("HTTP 206 for other bytes than asked");
        verdict = Verdict::transient;
        why = "the server sent another range than asked";
      }
    } else if (result.code == CURLE_OK && result.status == 416) {
      // Range Not Satisfiable: the file on the server is shorter than the partial one.
      r.restart_unresumed("HTTP 416, Range Not Satisfiable");
      verdict = Verdict::transient;
    }
    if (verdict == Verdict::done) return "";
    if (verdict == Verdict::permanent) return url + ": " + why;
    // A transfer that moved a resumable file forward does not count against the attempts.
    if (r.have() > before && !r.if_range().empty())
      failures = 0;
    else
      ++failures;
    if (failures >= std::max(1U, p.options.attempts))
      return url + ": " + why + " (gave up after " + std::to_string(failures) + " attempts)";
    sleep_seconds(backoff(p.options, failures == 0 ? 0 : failures - 1, wait));
    if_range = r.if_range();
    if (if_range.empty() && r.have() > 0) r.restart();
  }
}

// True when the store lists the entry with its SHA-256 and the file is there, of its size.
bool present_in(const fs::path& store, const Manifest& local, const ManifestEntry& e) {
  const auto* listed = local.find(e.file);
  if (listed == nullptr || listed->sha256 != e.sha256) return false;
  std::error_code ec;
  const auto status = fs::symlink_status(store / e.file, ec);
  return fs::is_regular_file(status) && fs::file_size(store / e.file, ec) == e.size;
}

// Why the store cannot take the entry, or "".
std::string conflict(const Manifest& local, const ManifestEntry& e) {
  const auto* listed = local.find(e.file);
  if (listed == nullptr || listed->sha256 == e.sha256) return "";
  return "the store already lists a different " + e.file + " (SHA-256 " +
         (listed->sha256.empty() ? std::string("unknown") : listed->sha256) + "), not replaced";
}

void fetch_entry(Puller& p, Http* http, PulledEntry& pulled) {
  const auto& e = pulled.entry;
  EntryLock lock(p.store, e.file);
  // Another pull may have placed it while this one waited for the entry.
  const auto current = Store::open(p.store).manifest();
  if (present_in(p.store, current, e)) {
    pulled.status = PullStatus::present;
    lock.remove_when_done();
    return;
  }
  if (auto why = conflict(current, e); !why.empty()) {
    pulled.status = PullStatus::refused;
    pulled.reason = {std::move(why)};
    return;
  }
  Receiver r(p, pulled, lock);
  const auto refuse = [&](Message why, bool keep_partial) {
    pulled.status = PullStatus::refused;
    pulled.reason = std::move(why);
    p.moved(-static_cast<std::int64_t>(r.have()));
    if (!keep_partial || r.have() == 0) lock.remove_when_done();
  };
  if (auto why = transfer(p, http, r, e); !why.empty()) {
    // A transfer that failed may be continued by the next pull; bytes that were wrong may not.
    const bool wrong_bytes = r.too_long();
    return refuse({std::move(why)}, !wrong_bytes);
  }
  if (r.have() != e.size)
    return refuse({bytes_text(r.have()) + " received, the MANIFEST says " + bytes_text(e.size)},
                  false);
  const auto sha = r.sha256();
  if (sha != e.sha256) return refuse({"SHA-256 " + sha + ", the MANIFEST says " + e.sha256}, false);
  r.sync_and_close();
  try {
    p.checks.run([&](VerifyWorkspace& workspace) {
      Store store = Store::open(p.store);
      Store::AddOptions add;
      add.move = true;
      add.expect = {e};
      add.sha256 = {sha};  // computed as the bytes arrived: not read again
      add.check_memory = p.options.check_memory;
      add.check_disk = p.options.check_disk;
      add.check_workspace = &workspace;
      store.add({r.data_path()}, add);
    });
  } catch (const Error& error) {
    return refuse(error.parts(), false);
  }
  pulled.status = PullStatus::fetched;
  lock.remove_when_done();
}

bool matches_any(const std::vector<std::string>& patterns, const std::vector<std::string>& names) {
  return std::any_of(patterns.begin(), patterns.end(), [&](const std::string& pattern) {
    return std::any_of(names.begin(), names.end(), [&](const std::string& name) {
      return ::fnmatch(pattern.c_str(), name.c_str(), 0) == 0;
    });
  });
}

// `bound`: with options.references_of, those of its instances the published store has solution
// files of.
bool selected(const ManifestEntry& e, const PullOptions& options,
              const std::set<std::string>& bound) {
  if (!options.references_of.empty() &&
      !(e.solutions ? options.references_of.contains(e.solutions->instance)
                    : bound.contains(e.digest)))
    return false;
  return (options.references || !e.solutions) &&
         (options.benchmarks.empty() || matches_any(options.benchmarks, {e.benchmark})) &&
         (options.views.empty() || matches_any(options.views, e.views)) &&
         (options.files.empty() || matches_any(options.files, {e.file}));
}

// Partial transfers from this source that can never be continued, because the published MANIFEST
// no longer lists their file or lists it with another SHA-256 than the one they were fetched for,
// are removed, each under its entry's lock taken without waiting (one a concurrent pull holds is
// left). Partials from other sources, or without validators, are not this pull's to judge.
void sweep_stale_partials(const fs::path& store, const Location& where, const Manifest& published) {
  const auto parent = store / kStagingDirectory / kPullDirectory;
  std::error_code ec;
  for (fs::directory_iterator it(parent, ec), end; !ec && it != end; it.increment(ec)) {
    const auto name = it->path().filename().string();
    if (!it->is_directory(ec) || it->is_symlink(ec)) continue;
    const auto v = read_validators(it->path() / kValidators);
    if (!v || v->url != where.url_of(name)) continue;
    const auto* listed = published.find(name);
    if (listed != nullptr && listed->sha256 == v->sha256) continue;
    Fd held{::open(it->path().c_str(), O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC)};
    if (held.fd < 0 || ::flock(held.fd, LOCK_EX | LOCK_NB) != 0) continue;
    std::error_code ignored;
    fs::remove_all(it->path(), ignored);
  }
}

}  // namespace

PullResult pull(const fs::path& store, std::string_view url, const PullOptions& options) {
  const auto started = Clock::now();
  const Location where = locate(url);
  if (where.http) start_curl();
  PullResult result;
  result.manifest_url = where.url_of(kManifestName);
  // The published list, checked in full before anything is fetched or written.
  const auto text = fetch_manifest(where, options, result.bytes);
  const auto published = parse_manifest(text, result.manifest_url);
  if (published.legacy)
    throw Error(result.manifest_url +
                ": an older TSV MANIFEST, which lists no SHA-256 to check the files against; "
                "the publisher's next `mosb store add` rewrites it");
  for (const auto& e : published.entries)
    if (is_reserved_store_name(e.file))
      throw Error(result.manifest_url + ": lists '" + e.file +
                  "', a name a store keeps for itself (MANIFEST, README.md, SUMMARY.csv, names "
                  "starting with '.')");
  std::set<std::string> bound;
  for (const auto& e : published.entries)
    if (e.solutions && options.references_of.contains(e.solutions->instance))
      bound.insert(e.solutions->instance);
  for (const auto& e : published.entries)
    if (selected(e, options, bound)) {
      PulledEntry pulled;
      pulled.entry = e;
      result.entries.push_back(std::move(pulled));
    }

  std::error_code ec;
  const bool exists = fs::exists(store / kManifestName, ec);
  const Manifest local = exists ? Store::open(store).manifest() : Manifest{};
  Puller puller(store, where, options);
  std::vector<PulledEntry*> to_fetch;
  for (auto& pulled : result.entries) {
    if (present_in(store, local, pulled.entry)) {
      pulled.status = PullStatus::present;
    } else if (auto why = conflict(local, pulled.entry); !why.empty()) {
      pulled.status = PullStatus::refused;
      pulled.reason = {std::move(why)};
    } else {
      to_fetch.push_back(&pulled);
      puller.total += pulled.entry.size;
    }
  }
  if (options.dry_run) {
    result.seconds = std::chrono::duration<double>(Clock::now() - started).count();
    return result;
  }
  if (!exists) {
    try {
      Store::init(store);
    } catch (const Error&) {
      if (!fs::exists(store / kManifestName, ec)) throw;  // else a concurrent pull made it
    }
  }

  puller.selected = result.entries.size();
  for (const auto& pulled : result.entries)
    if (pulled.status != PullStatus::planned) puller.settled(pulled);
  if (puller.total > 0) report(options.progress, "pull", 0, puller.total);
  // A worker's libcurl handle serves all its transfers, so its connections are kept.
  const auto connect = [&](unsigned) {
    return where.http ? std::make_unique<Http>(options.stall_timeout_seconds) : nullptr;
  };
  // Instances first: a solution file is checked against its instance in the store.
  std::stable_partition(to_fetch.begin(), to_fetch.end(),
                        [](const PulledEntry* p) { return !p->entry.solutions; });
  const auto instances = static_cast<std::size_t>(std::count_if(
      to_fetch.begin(), to_fetch.end(), [](const PulledEntry* p) { return !p->entry.solutions; }));
  for (const auto& range :
       {std::pair{std::size_t{0}, instances}, std::pair{instances, to_fetch.size()}})
    parallel_for_with_state(
        range.second - range.first, std::max(1U, options.jobs), connect,
        [&](std::unique_ptr<Http>& http, std::size_t k) {
          auto& pulled = *to_fetch[range.first + k];
          try {
            fetch_entry(puller, http.get(), pulled);
          } catch (const Error& error) {  // the store's own trouble (I/O, a planted link)
            pulled.status = PullStatus::refused;
            pulled.reason = error.parts();
          } catch (const std::exception& error) {
            pulled.status = PullStatus::refused;
            pulled.reason = {error.what()};
          }
          puller.settled(pulled);
        });
  if (puller.total > 0) report(options.progress, "pull", puller.total, puller.total);
  sweep_stale_partials(store, where, published);
  ::rmdir((store / kStagingDirectory / kPullDirectory).c_str());  // when empty
  ::rmdir((store / kStagingDirectory).c_str());

  if (options.unpack) {
    const auto placed = Store::open(store);
    for (auto& pulled : result.entries) {
      if (pulled.status == PullStatus::refused || !pulled.entry.packed) continue;
      try {
        placed.unpack(pulled.entry.file);
      } catch (const Error& error) {
        pulled.status = PullStatus::refused;
        pulled.reason = error.with_context("listed, but not unpacked: ").parts();
      }
    }
  }
  result.bytes += puller.received;
  result.seconds = std::chrono::duration<double>(Clock::now() - started).count();
  return result;
}

bool is_store_url(std::string_view source) {
  return source.starts_with("http://") || source.starts_with("https://") ||
         source.starts_with("file://");
}

fs::path store_cache(std::string_view url) {
  while (url.size() > 1 && url.back() == '/') url.remove_suffix(1);
  const auto key = sha256_hex(std::as_bytes(std::span(url.data(), url.size()))).substr(0, 16);
  if (const char* dir = std::getenv("MOSB_STORE_CACHE"); dir && *dir) return fs::path(dir) / key;
  if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg && *xdg)
    return fs::path(xdg) / "mosb" / "stores" / key;
  if (const char* home = std::getenv("HOME"); home && *home)
    return fs::path(home) / ".cache" / "mosb" / "stores" / key;
  throw Error(ErrorCode::invalid_argument,
              "no place to pull " + std::string(url) +
                  " into: set MOSB_STORE_CACHE, XDG_CACHE_HOME or HOME, or pull it with mosb "
                  "store pull DIR URL and give DIR");
}

}  // namespace mosb
