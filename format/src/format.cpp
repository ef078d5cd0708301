#include "mosb/format.hpp"

namespace mosb::format {

std::optional<ElementType> element_type_from(std::uint8_t raw) {
  if (raw >= 1 && raw <= 10) return static_cast<ElementType>(raw);
  return std::nullopt;
}

std::optional<SectionKind> section_kind_from(std::uint16_t raw) {
  if (raw >= 1 && raw <= kLastSectionKind) return static_cast<SectionKind>(raw);
  return std::nullopt;
}

std::string_view to_string(Encoding e) {
  switch (e) {
    case Encoding::raw:
      return "raw";
    case Encoding::zstd:
      return "zstd";
    case Encoding::shuffle_zstd:
      return "shuffle-zstd";
    case Encoding::delta_zstd:
      return "delta-zstd";
    case Encoding::transpose:
      return "transpose";
  }
  return {};
}

std::string_view to_string(ElementType t) {
  switch (t) {
    case ElementType::u8:
      return "u8";
    case ElementType::u16:
      return "u16";
    case ElementType::u32:
      return "u32";
    case ElementType::u64:
      return "u64";
    case ElementType::i8:
      return "i8";
    case ElementType::i16:
      return "i16";
    case ElementType::i32:
      return "i32";
    case ElementType::i64:
      return "i64";
    case ElementType::f32:
      return "f32";
    case ElementType::f64:
      return "f64";
  }
  return "?";
}

std::string_view to_string(FileKind k) {
  switch (k) {
    case FileKind::instance:
      return "graph instance";
    case FileKind::solutions:
      return "solution file";
  }
  return {};
}

std::string_view to_string(SectionKind k) {
  switch (k) {
    case SectionKind::metadata:
      return "metadata";
    case SectionKind::forward_offsets:
      return "forward_offsets";
    case SectionKind::forward_targets:
      return "forward_targets";
    case SectionKind::reverse_offsets:
      return "reverse_offsets";
    case SectionKind::reverse_sources:
      return "reverse_sources";
    case SectionKind::reverse_arcs:
      return "reverse_arcs";
    case SectionKind::cost:
      return "cost";
    case SectionKind::vertex_data:
      return "vertex_data";
    case SectionKind::arc_data:
      return "arc_data";
    case SectionKind::queries:
      return "queries";
    case SectionKind::solution_status:
      return "solution_status";
    case SectionKind::front_offsets:
      return "front_offsets";
    case SectionKind::front_cost:
      return "front_cost";
    case SectionKind::solution_statistics:
      return "solution_statistics";
    case SectionKind::path_offsets:
      return "path_offsets";
    case SectionKind::path_vertices:
      return "path_vertices";
    case SectionKind::query_reference:
      return "query_reference";
  }
  return "?";
}

std::optional<ElementType> parse_element_type(std::string_view name) {
  for (std::uint8_t raw = 1; raw <= 10; ++raw) {
    auto t = static_cast<ElementType>(raw);
    if (to_string(t) == name) return t;
  }
  return std::nullopt;
}

}  // namespace mosb::format
