// Prints everything in a mosb file as JSON, through the C++ reader, for
// spec/reference/compare_dump.py: the independent Python reader must see exactly the same values.
// Usage: mosb_dump_json FILE
#include <cmath>
#include <cstdio>
#include <iostream>

#include "mosb/graph_reader.hpp"
#include "mosb/internal/hex.hpp"

using namespace mosb;
using format::ElementType;

namespace {

std::string json_string(std::string_view s) {
  std::string out = "\"";
  for (unsigned char c : s) {
    if (c == '"' || c == '\\')
      out += '\\', out += static_cast<char>(c);
    else if (c < 0x20) {
      char buffer[8];
      std::snprintf(buffer, sizeof buffer, "\\u%04x", c);
      out += buffer;
    } else
      out += static_cast<char>(c);
  }
  return out + "\"";
}

template <class T>
void print_values(const GraphReader& r, const Section& s) {
  const char* separator = "";
  for (T v : r.values<T>(s)) {
    std::cout << separator;
    separator = ",";
    if constexpr (std::is_floating_point_v<T>) {
      if (std::isnan(v))
        std::cout << "\"nan\"";
      else if (std::isinf(v))
        std::cout << (v > 0 ? "\"inf\"" : "\"-inf\"");
      else {
        char buffer[40];
        std::snprintf(buffer, sizeof buffer, "%.17g", static_cast<double>(v));
        std::cout << buffer;
      }
    } else {
      std::cout << +v;
    }
  }
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::cerr << "usage: mosb_dump_json FILE\n";
    return 2;
  }
  try {
    const auto r = GraphReader::open(argv[1]);
    std::cout << "{\"n\":" << r.vertex_count() << ",\"m\":" << r.arc_count() << ",\"version\":["
              << r.header().version_major << "," << r.header().version_minor << "],\"metadata\":{";
    const char* separator = "";
    for (const auto& [key, value] : r.metadata().entries()) {
      std::cout << separator << json_string(key) << ":" << json_string(value);
      separator = ",";
    }
    std::cout << "},\"sections\":[";
    separator = "";
    for (const auto& s : r.sections()) {
      std::cout << separator << "{\"name\":" << json_string(s.name) << ",\"kind\":" << s.entry.kind
                << ",\"type\":\"" << format::to_string(s.type)
                << "\",\"width\":" << s.entry.row_width << ",\"rows\":" << s.entry.row_count
                << ",\"checksum\":\"" << hex64(s.entry.checksum) << "\"";
      separator = ",";
      if (s.kind != format::SectionKind::metadata) {
        std::cout << ",\"values\":[";
        switch (s.type) {
          case ElementType::u8:
            print_values<std::uint8_t>(r, s);
            break;
          case ElementType::u16:
            print_values<std::uint16_t>(r, s);
            break;
          case ElementType::u32:
            print_values<std::uint32_t>(r, s);
            break;
          case ElementType::u64:
            print_values<std::uint64_t>(r, s);
            break;
          case ElementType::i8:
            print_values<std::int8_t>(r, s);
            break;
          case ElementType::i16:
            print_values<std::int16_t>(r, s);
            break;
          case ElementType::i32:
            print_values<std::int32_t>(r, s);
            break;
          case ElementType::i64:
            print_values<std::int64_t>(r, s);
            break;
          case ElementType::f32:
            print_values<float>(r, s);
            break;
          case ElementType::f64:
            print_values<double>(r, s);
            break;
        }
        std::cout << "]";
      }
      std::cout << "}";
    }
    std::cout << "]}\n";
  } catch (const Error& e) {
    std::cerr << e.what() << '\n';
    return 1;
  }
  return 0;
}
