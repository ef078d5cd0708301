// The `--json` output of the CLI: a builder-style writer (begin/key/value/end) whose every scalar
// and key is serialized by nlohmann::json, so that every JSON byte mosb prints comes from one
// well-kept library. Each top-level value is printed compactly, with object keys in the order
// written, followed by a newline when it closes; nothing of it is printed before then, so an error
// while building it prints no half a document.
//
// Linear in what is written: the document is appended to a buffer as it is built (a tree of
// nlohmann::ordered_json, whose operator[] scans an object's keys, made `inspect --json` of a file
// with 20,000 views quadratic). Keys are unique per object by construction (literals, or the keys
// of a std::map); a key written twice in one object is a bug of the caller and throws
// std::logic_error instead of printing a document with a duplicate key.
#pragma once

#include <cmath>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <optional>
#include <ostream>
#include <stdexcept>
#include <string>
#include <string_view>
#include <unordered_set>
#include <vector>

namespace mosb::cli {

class JsonWriter {
 public:
  using Json = nlohmann::ordered_json;

  explicit JsonWriter(std::ostream& out) : out_(out) {}

  JsonWriter& begin_object() { return open('{', true); }
  JsonWriter& end_object() { return close('}'); }
  JsonWriter& begin_array() { return open('[', false); }
  JsonWriter& end_array() { return close(']'); }
  JsonWriter& key(std::string_view k) {
    key_ = std::string(k);
    return *this;
  }
  JsonWriter& value(std::string_view v) { return scalar(Json(std::string(v))); }
  JsonWriter& value(const char* v) { return value(std::string_view(v)); }
  JsonWriter& value(std::uint64_t v) { return scalar(Json(v)); }
  JsonWriter& value(bool v) { return scalar(Json(v)); }
  // JSON has no NaN or infinity: null.
  JsonWriter& value(double v) { return scalar(std::isfinite(v) ? Json(v) : Json(nullptr)); }
  JsonWriter& null() { return scalar(Json(nullptr)); }
  // An absent value is null.
  template <class T>
  JsonWriter& value(const std::optional<T>& v) {
    return v ? value(*v) : null();
  }

 private:
  struct Container {
    bool object = false;
    bool empty = true;
    std::unordered_set<std::string> keys;  // of an object, to refuse a key written twice
  };

  // Invalid UTF-8 (say, in a file name) becomes U+FFFD instead of failing the report.
  void append(const Json& v) { buffer_ += v.dump(-1, ' ', false, Json::error_handler_t::replace); }
  // What comes before a value: a comma after a sibling, and inside an object the pending key.
  void separate() {
    if (open_.empty()) return;
    auto& parent = open_.back();
    if (!parent.empty) buffer_ += ',';
    parent.empty = false;
    if (!parent.object) return;
    if (!parent.keys.insert(key_).second)
      throw std::logic_error("JSON key '" + key_ + "' written twice in one object");
    append(Json(key_));
    buffer_ += ':';
  }
  JsonWriter& scalar(const Json& v) {
    separate();
    append(v);
    if (open_.empty()) print();
    return *this;
  }
  JsonWriter& open(char bracket, bool object) {
    separate();
    buffer_ += bracket;
    open_.push_back({object, true, {}});
    return *this;
  }
  JsonWriter& close(char bracket) {
    buffer_ += bracket;
    open_.pop_back();
    if (open_.empty()) print();
    return *this;
  }
  void print() {
    out_ << buffer_ << '\n';
    buffer_.clear();
  }

  std::ostream& out_;
  std::string buffer_;  // the top-level value being built
  std::vector<Container> open_;
  std::string key_;
};

}  // namespace mosb::cli
