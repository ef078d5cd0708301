// A minimal streaming JSON writer for `--json` output (Boost 1.74 has no Boost.JSON).
#pragma once

#include <charconv>
#include <cmath>
#include <cstdint>
#include <ostream>
#include <string_view>
#include <vector>

#include "mosb/utf8.hpp"

namespace mosb::cli {

class JsonWriter {
 public:
  explicit JsonWriter(std::ostream& out) : out_(out) {}

  JsonWriter& begin_object() { return open('{'); }
  JsonWriter& end_object() { return close('}'); }
  JsonWriter& begin_array() { return open('['); }
  JsonWriter& end_array() { return close(']'); }
  JsonWriter& key(std::string_view k) {
    separate();
    write_string(k);
    out_ << ':';
    after_key_ = true;
    return *this;
  }
  JsonWriter& value(std::string_view v) {
    return scalar([&] { write_string(v); });
  }
  JsonWriter& value(const char* v) { return value(std::string_view(v)); }
  JsonWriter& value(std::uint64_t v) {
    return scalar([&] { out_ << v; });
  }
  JsonWriter& value(bool v) {
    return scalar([&] { out_ << (v ? "true" : "false"); });
  }
  // Shortest text that reads back as the same double; JSON has no NaN or infinity: null.
  JsonWriter& value(double v) {
    return scalar([&] {
      if (!std::isfinite(v)) {
        out_ << "null";
        return;
      }
      char buffer[32];
      const auto end = std::to_chars(buffer, buffer + sizeof buffer, v).ptr;
      out_.write(buffer, end - buffer);
    });
  }
  JsonWriter& null() {
    return scalar([&] { out_ << "null"; });
  }

 private:
  template <class F>
  JsonWriter& scalar(F write) {
    separate();
    write();
    return *this;
  }
  JsonWriter& open(char c) {
    separate();
    out_ << c;
    first_.push_back(true);
    return *this;
  }
  JsonWriter& close(char c) {
    out_ << c;
    first_.pop_back();
    if (first_.empty()) out_ << '\n';
    return *this;
  }
  void separate() {
    if (after_key_) {
      after_key_ = false;
      return;
    }
    if (!first_.empty()) {
      if (!first_.back()) out_ << ',';
      first_.back() = false;
    }
  }
  void write_string(std::string_view s) {
    out_ << '"';
    for (std::size_t i = 0; i < s.size(); ++i) {
      const auto c = static_cast<unsigned char>(s[i]);
      if (c >= 0x80) {  // JSON must be UTF-8: a stray byte (say, in a file name) becomes U+FFFD
        const auto length = utf8_sequence_length(s, i);
        if (length == 0)
          out_ << "\\ufffd";
        else
          out_ << s.substr(i, length);
        i += length == 0 ? 0 : length - 1;
      } else if (c == '"' || c == '\\')
        out_ << '\\' << c;
      else if (c == '\n')
        out_ << "\\n";
      else if (c == '\t')
        out_ << "\\t";
      else if (c < 0x20) {
        static constexpr char kHex[] = "0123456789abcdef";
        out_ << "\\u00" << kHex[c >> 4] << kHex[c & 15];
      } else
        out_ << c;
    }
    out_ << '"';
  }

  std::ostream& out_;
  std::vector<bool> first_;
  bool after_key_ = false;
};

}  // namespace mosb::cli
