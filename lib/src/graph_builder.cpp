#include "mosb/graph_builder.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "mosb/error.hpp"
#include "mosb/file_writer.hpp"
#include "mosb/version.hpp"

namespace mosb {

using format::ElementType;
using format::SectionKind;

namespace {

template <class Out, class In>
bool fits_exactly(In value) {
  if constexpr (std::is_floating_point_v<In> && std::is_integral_v<Out>) {
    if (!(value >= 0) || value != std::floor(value)) return false;
    // 2^64 as a double: anything at or above it does not fit any unsigned type.
    if (value >= 18446744073709551616.0) return false;
    return static_cast<std::uint64_t>(value) <= std::numeric_limits<Out>::max();
  } else if constexpr (std::is_integral_v<In> && std::is_integral_v<Out>) {
    return value <= std::numeric_limits<Out>::max();
  } else {
    return static_cast<In>(static_cast<Out>(value)) == value;
  }
}

template <class Out, class In>
std::optional<std::size_t> first_misfit(const std::vector<In>& values) {
  for (std::size_t i = 0; i < values.size(); ++i)
    if (!fits_exactly<Out>(values[i])) return i;
  return std::nullopt;
}

template <class In>
std::optional<std::size_t> first_misfit_as(ElementType type, const std::vector<In>& values) {
  return format::visit_element_type(type, [&](auto tag) -> std::optional<std::size_t> {
    using Out = typename decltype(tag)::type;
    if constexpr (format::is_cost_type_v<Out>) return first_misfit<Out>(values);
    return 0;
  });
}

template <class T>
std::string value_text(T value) {
  if constexpr (std::is_floating_point_v<T>) {
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, "%.17g", value);
    return buffer;
  } else {
    return std::to_string(value);
  }
}

// Streams `values` permuted by `order` (order[p] = input index of output row p) as type Out.
template <class Out, class In>
void write_permuted(FileWriter& writer, const std::vector<In>& values,
                    const std::vector<std::uint32_t>& order) {
  constexpr std::size_t kChunk = 1 << 14;
  Out chunk[kChunk];
  std::size_t filled = 0;
  for (std::uint32_t index : order) {
    chunk[filled++] = static_cast<Out>(values[index]);
    if (filled == kChunk) {
      writer.append_values(std::span<const Out>(chunk, filled));
      filled = 0;
    }
  }
  writer.append_values(std::span<const Out>(chunk, filled));
}

template <class In>
void write_cost(FileWriter& writer, ElementType type, const std::vector<In>& values,
                const std::vector<std::uint32_t>& order) {
  format::visit_element_type(type, [&](auto tag) {
    using Out = typename decltype(tag)::type;
    if constexpr (format::is_cost_type_v<Out>)
      write_permuted<Out>(writer, values, order);
    else
      throw Error("internal error: cost type " + std::string(format::to_string(type)));
  });
}

void check_name(std::string_view what, const std::string& name) {
  if (name.empty() || name.size() > format::kNameSize || !Metadata::is_valid_key(name))
    throw Error(std::string(what) + " name '" + name +
                "' must be 1-24 characters from [A-Za-z0-9_.+-]");
}

template <class Item>
void check_unique_names(std::string_view what, const std::vector<Item>& items) {
  for (std::size_t i = 0; i < items.size(); ++i) {
    check_name(what, items[i].name);
    for (std::size_t j = 0; j < i; ++j)
      if (items[i].name == items[j].name)
        throw Error(std::string(what) + " name '" + items[i].name + "' is used twice");
  }
}

void check_input(const GraphInput& in) {
  const std::uint64_t n = in.vertex_count;
  const std::uint64_t m = in.tails.size();
  if (n >= std::numeric_limits<std::uint32_t>::max())
    throw Error("vertex count " + std::to_string(n) + " exceeds the format limit of 2^32-2");
  if (m >= std::numeric_limits<std::uint32_t>::max())
    throw Error("arc count " + std::to_string(m) + " exceeds the format limit of 2^32-2");
  if (in.heads.size() != m) throw Error("arc list has " + std::to_string(m) + " tails but " +
                                        std::to_string(in.heads.size()) + " heads");
  for (std::uint64_t a = 0; a < m; ++a)
    if (in.tails[a] >= n || in.heads[a] >= n)
      throw Error("arc " + std::to_string(a) + " (" + std::to_string(in.tails[a]) + " -> " +
                  std::to_string(in.heads[a]) + ") has an endpoint not below the vertex count " +
                  std::to_string(n));
  check_unique_names("objective", in.costs);
  check_unique_names("vertex data", in.vertex_data);
  check_unique_names("arc data", in.arc_data);
  check_unique_names("query set", in.queries);
  for (const auto& c : in.costs) {
    auto size = std::visit([](const auto& v) { return v.size(); }, c.values);
    if (size != m) throw Error("objective '" + c.name + "' has " + std::to_string(size) +
                               " costs for " + std::to_string(m) + " arcs");
  }
  auto check_rows = [](const DataColumn& d, std::uint64_t rows, std::string_view per) {
    const std::uint64_t row_bytes = d.width * format::element_size(d.type);
    if (row_bytes == 0 || d.bytes.size() != rows * row_bytes)
      throw Error("data column '" + d.name + "' must hold one row of " + std::to_string(d.width) +
                  " " + std::string(format::to_string(d.type)) + " per " + std::string(per));
  };
  for (const auto& d : in.vertex_data) check_rows(d, n, "vertex");
  for (const auto& d : in.arc_data) check_rows(d, m, "arc");
  for (const auto& q : in.queries)
    for (std::size_t i = 0; i < q.pairs.size(); ++i)
      if (q.pairs[i].start >= n || q.pairs[i].goal >= n)
        throw Error("query set '" + q.name + "', query " + std::to_string(i) +
                    ": an endpoint is not below the vertex count " + std::to_string(n));
}

}  // namespace

format::ElementType choose_cost_type(const CostColumn& column) {
  return std::visit(
      [&](const auto& values) -> ElementType {
        using In = typename std::decay_t<decltype(values)>::value_type;
        if constexpr (std::is_floating_point_v<In>) {
          for (std::size_t i = 0; i < values.size(); ++i)
            if (!std::isfinite(values[i]) || values[i] < 0)
              throw Error("objective '" + column.name + "', arc " + std::to_string(i) + ": cost " +
                          value_text(values[i]) + " is not a finite non-negative number");
        }
        if (column.forced_type) {
          const ElementType type = *column.forced_type;
          if (!format::is_unsigned(type) && !format::is_float(type))
            throw Error("objective '" + column.name + "': cost type " +
                        std::string(format::to_string(type)) + " is not unsigned or float");
          if (auto i = first_misfit_as(type, values))
            throw Error("objective '" + column.name + "', arc " + std::to_string(*i) + ": cost " +
                        value_text(values[*i]) + " is not exactly representable as " +
                        std::string(format::to_string(type)));
          return type;
        }
        if constexpr (std::is_floating_point_v<In>) {
          return first_misfit<float>(values) ? ElementType::f64 : ElementType::f32;
        } else {
          const std::uint64_t max = values.empty() ? 0 : *std::max_element(values.begin(), values.end());
          if (max <= std::numeric_limits<std::uint8_t>::max()) return ElementType::u8;
          if (max <= std::numeric_limits<std::uint16_t>::max()) return ElementType::u16;
          if (max <= std::numeric_limits<std::uint32_t>::max()) return ElementType::u32;
          return ElementType::u64;
        }
      },
      column.values);
}

void write_graph(const GraphInput& in, const std::filesystem::path& path) {
  check_input(in);
  const std::uint64_t n = in.vertex_count;
  const std::size_t m = in.tails.size();

  std::vector<ElementType> cost_types;
  std::vector<std::string> cost_names, query_names;
  for (const auto& c : in.costs) {
    cost_types.push_back(choose_cost_type(c));
    cost_names.push_back(c.name);
  }
  for (const auto& q : in.queries) query_names.push_back(q.name);
  Metadata metadata = in.metadata;
  for (const auto& c : in.costs) metadata.set("objective." + c.name + ".unit", c.unit);
  // An input may name the program that made it (a converter of another tool, a pinned test).
  if (!metadata.get("source.tool")) metadata.set("source.tool", std::string("mosb ") + kVersion);
  if (auto problem = find_view_problem(metadata, cost_names, query_names)) throw Error(*problem);

  // Counting sort by tail; iterating arcs in input order keeps it stable.
  std::vector<std::uint64_t> offsets(n + 1, 0);
  for (auto t : in.tails) ++offsets[t + 1];
  for (std::uint64_t v = 0; v < n; ++v) offsets[v + 1] += offsets[v];
  std::vector<std::uint32_t> order(m);  // order[p] = input index of CSR arc p
  {
    std::vector<std::uint64_t> cursor(offsets.begin(), offsets.end() - 1);
    for (std::uint32_t a = 0; a < m; ++a) order[cursor[in.tails[a]]++] = a;
  }
  std::vector<std::uint32_t> targets(m);
  for (std::size_t p = 0; p < m; ++p) targets[p] = in.heads[order[p]];

  // The transpose: scanning forward arcs in id order makes each in-list ascending by arc id.
  std::vector<std::uint64_t> reverse_offsets(n + 1, 0);
  for (auto h : targets) ++reverse_offsets[h + 1];
  for (std::uint64_t v = 0; v < n; ++v) reverse_offsets[v + 1] += reverse_offsets[v];
  std::vector<std::uint32_t> reverse_sources(m), reverse_arcs(m);
  {
    std::vector<std::uint64_t> cursor(reverse_offsets.begin(), reverse_offsets.end() - 1);
    for (std::uint32_t u = 0; u < n; ++u)
      for (auto p = offsets[u]; p < offsets[u + 1]; ++p) {
        auto slot = cursor[targets[p]]++;
        reverse_sources[slot] = u;
        reverse_arcs[slot] = static_cast<std::uint32_t>(p);
      }
  }

  FileWriter writer(path);
  const std::string metadata_text = metadata.serialize();
  writer.add_section(SectionKind::metadata, "metadata", 1,
                     std::span(reinterpret_cast<const std::uint8_t*>(metadata_text.data()),
                               metadata_text.size()));
  writer.add_section(SectionKind::forward_offsets, "forward_offsets", 1, std::span<const std::uint64_t>(offsets));
  writer.add_section(SectionKind::forward_targets, "forward_targets", 1, std::span<const std::uint32_t>(targets));
  writer.add_section(SectionKind::reverse_offsets, "reverse_offsets", 1,
                     std::span<const std::uint64_t>(reverse_offsets));
  writer.add_section(SectionKind::reverse_sources, "reverse_sources", 1,
                     std::span<const std::uint32_t>(reverse_sources));
  writer.add_section(SectionKind::reverse_arcs, "reverse_arcs", 1, std::span<const std::uint32_t>(reverse_arcs));
  for (std::size_t i = 0; i < in.costs.size(); ++i) {
    writer.begin_section(SectionKind::cost, in.costs[i].name, cost_types[i], 1);
    std::visit([&](const auto& values) { write_cost(writer, cost_types[i], values, order); },
               in.costs[i].values);
    writer.end_section();
  }
  for (const auto& d : in.arc_data) {
    const std::size_t row_bytes = d.width * format::element_size(d.type);
    writer.begin_section(SectionKind::arc_data, d.name, d.type, d.width);
    for (auto index : order)
      writer.append(std::span(d.bytes).subspan(index * row_bytes, row_bytes));
    writer.end_section();
  }
  for (const auto& d : in.vertex_data) {
    writer.begin_section(SectionKind::vertex_data, d.name, d.type, d.width);
    writer.append(std::span(d.bytes));
    writer.end_section();
  }
  for (const auto& q : in.queries) {
    writer.begin_section(SectionKind::queries, q.name, ElementType::u32, 2);
    writer.append(std::as_bytes(std::span(q.pairs)));
    writer.end_section();
  }
  writer.commit(n, m);
}

}  // namespace mosb
