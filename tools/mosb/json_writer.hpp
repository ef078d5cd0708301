// The `--json` output of the CLI: a builder-style writer (begin/key/value/end) over nlohmann::json,
// so that every JSON byte mosb prints comes from one well-kept library. Each top-level value is
// printed compactly, with object keys in insertion order, followed by a newline when it closes.
#pragma once

#include <cmath>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <optional>
#include <ostream>
#include <string>
#include <string_view>
#include <vector>

namespace mosb::cli {

class JsonWriter {
 public:
  using Json = nlohmann::ordered_json;

  explicit JsonWriter(std::ostream& out) : out_(out) {}

  JsonWriter& begin_object() { return open(Json::object()); }
  JsonWriter& end_object() { return close(); }
  JsonWriter& begin_array() { return open(Json::array()); }
  JsonWriter& end_array() { return close(); }
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
  // Places v inside the innermost open container (under the pending key of an object) and returns
  // where it now lives; a value outside any container is printed at once.
  Json* place(Json v) {
    if (open_.empty()) {
      root_ = std::move(v);
      return &root_;
    }
    Json& parent = *open_.back();
    if (parent.is_array()) {
      parent.push_back(std::move(v));
      return &parent.back();
    }
    Json& slot = parent[key_];
    slot = std::move(v);
    return &slot;
  }
  JsonWriter& scalar(Json v) {
    place(std::move(v));
    if (open_.empty()) print();
    return *this;
  }
  JsonWriter& open(Json container) {
    // Only the innermost open container grows, so pointers to the enclosing ones stay valid.
    open_.push_back(place(std::move(container)));
    return *this;
  }
  JsonWriter& close() {
    open_.pop_back();
    if (open_.empty()) print();
    return *this;
  }
  void print() {
    // Invalid UTF-8 (say, in a file name) becomes U+FFFD instead of failing the report.
    out_ << root_.dump(-1, ' ', false, Json::error_handler_t::replace) << '\n';
    root_ = Json();
  }

  std::ostream& out_;
  Json root_;
  std::vector<Json*> open_;
  std::string key_;
};

}  // namespace mosb::cli
