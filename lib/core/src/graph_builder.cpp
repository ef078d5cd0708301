#include "mosb/graph_builder.hpp"

#include <algorithm>
#include <cmath>
#include <exception>
#include <limits>
#include <system_error>
#include <thread>

#include "mosb/error.hpp"
#include "mosb/file_writer.hpp"
#include "mosb/internal/large_array.hpp"
#include "mosb/internal/transpose.hpp"
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

// `values` permuted by `order` (order[p] = input index of output row p) as the stored bytes of
// cost type `type`.
template <class In>
LargeArray<std::byte> permuted_cost(ElementType type, const std::vector<In>& values,
                                    std::span<const std::uint32_t> order) {
  LargeArray<std::byte> bytes;
  format::visit_element_type(type, [&](auto tag) {
    using Out = typename decltype(tag)::type;
    if constexpr (format::is_cost_type_v<Out>) {
      bytes.resize(order.size() * sizeof(Out));
      auto* out = reinterpret_cast<Out*>(bytes.data());
      for (std::size_t p = 0; p < order.size(); ++p) out[p] = static_cast<Out>(values[order[p]]);
    } else {
      throw Error("internal error: cost type " + std::string(format::to_string(type)));
    }
  });
  return bytes;
}

ElementType narrowest_unsigned(std::uint64_t max);
void check_counts(std::uint64_t n, std::uint64_t m);
void check_queries(const std::vector<QuerySet>& queries, std::uint64_t n);

void check_name(std::string_view what, const std::string& name) {
  if (!format::is_valid_section_name(name))
    throw Error(std::string(what) + " name '" + name + "' must be " +
                std::string(format::kSectionNameRule));
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

void check_rows(const DataColumn& d, std::uint64_t rows, std::string_view per) {
  const std::uint64_t row_bytes = d.width * format::element_size(d.type);
  if (row_bytes == 0 || d.bytes.size() != rows * row_bytes)
    throw Error("data column '" + d.name + "' must hold one row of " + std::to_string(d.width) +
                " " + std::string(format::to_string(d.type)) + " per " + std::string(per));
}

void check_input(const GraphInput& in) {
  const std::uint64_t n = in.vertex_count;
  const std::uint64_t m = in.tails.size();
  check_counts(n, m);
  if (in.heads.size() != m)
    throw Error("arc list has " + std::to_string(m) + " tails but " +
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
    if (size != m)
      throw Error("objective '" + c.name + "' has " + std::to_string(size) + " costs for " +
                  std::to_string(m) + " arcs");
  }
  for (const auto& d : in.vertex_data) check_rows(d, n, "vertex");
  for (const auto& d : in.arc_data) check_rows(d, m, "arc");
  check_queries(in.queries, n);
}

ElementType narrowest_unsigned(std::uint64_t max) {
  if (max <= std::numeric_limits<std::uint8_t>::max()) return ElementType::u8;
  if (max <= std::numeric_limits<std::uint16_t>::max()) return ElementType::u16;
  if (max <= std::numeric_limits<std::uint32_t>::max()) return ElementType::u32;
  return ElementType::u64;
}

void check_counts(std::uint64_t n, std::uint64_t m) {
  if (n > format::kMaxCount)
    throw Error("vertex count " + std::to_string(n) + " exceeds the format limit of 2^32-2");
  if (m > format::kMaxCount)
    throw Error("arc count " + std::to_string(m) + " exceeds the format limit of 2^32-2");
}

void check_queries(const std::vector<QuerySet>& queries, std::uint64_t n) {
  for (const auto& q : queries)
    for (std::size_t i = 0; i < q.pairs.size(); ++i)
      if (q.pairs[i].start >= n || q.pairs[i].goal >= n)
        throw Error("query set '" + q.name + "', query " + std::to_string(i) +
                    ": an endpoint is not below the vertex count " + std::to_string(n));
}

// The stored metadata: the input's, the unit of every objective and the writing tool.
template <class Cost>
Metadata stored_metadata(const Metadata& input, const std::vector<Cost>& costs,
                         const std::vector<QuerySet>& queries) {
  std::vector<std::string> cost_names, query_names;
  for (const auto& c : costs) cost_names.push_back(c.name);
  for (const auto& q : queries) query_names.push_back(q.name);
  Metadata metadata = input;
  for (const auto& c : costs) metadata.set("objective." + c.name + ".unit", c.unit);
  // An input may name the program that made it (a converter of another tool, a pinned test).
  if (!metadata.get("source.tool")) metadata.set("source.tool", std::string("mosb ") + kVersion);
  if (auto problem = find_view_problem(metadata, cost_names, query_names)) throw Error(*problem);
  for (const auto& q : queries) add_reference_metadata(metadata, q, cost_names, "");
  return metadata;
}

void add_metadata_section(FileWriter& writer, const Metadata& metadata) {
  const std::string text = metadata.serialize();
  writer.add_section(SectionKind::metadata, "metadata", 1,
                     std::span(reinterpret_cast<const std::uint8_t*>(text.data()), text.size()));
}

void add_query_sections(FileWriter& writer, const std::vector<QuerySet>& queries) {
  for (const auto& q : queries) write_query_set(writer, q);
}

// Appends values one at a time through a fixed buffer.
template <class T>
class ChunkedAppender {
 public:
  explicit ChunkedAppender(FileWriter& writer) : writer_(writer) { chunk_.reserve(kChunk); }
  void push(T value) {
    chunk_.push_back(value);
    if (chunk_.size() == kChunk) flush();
  }
  void flush() {
    writer_.append_values(std::span<const T>(chunk_));
    chunk_.clear();
  }

 private:
  static constexpr std::size_t kChunk = 1 << 14;
  FileWriter& writer_;
  std::vector<T> chunk_;
};

// Counts arcs over every pass of the streamed writer and reports every 2^20 of them.
class PassCounter {
 public:
  PassCounter(const Progress& progress, std::uint64_t total) : progress_(progress), total_(total) {
    report(progress_, "write", 0, total_);
  }
  void tick() {
    if ((++done_ & 0xFFFFF) == 0) report(progress_, "write", done_, total_);
  }
  void finish() { report(progress_, "write", total_, total_); }

 private:
  const Progress& progress_;
  std::uint64_t total_;
  std::uint64_t done_ = 0;
};

void write_vertex_data(FileWriter& writer, const std::vector<DataColumn>& columns) {
  for (const auto& d : columns) {
    writer.begin_section(SectionKind::vertex_data, d.name, d.type, d.width);
    writer.append(std::span(d.bytes));
    writer.end_section();
  }
}

template <class Out>
void write_streamed_cost(FileWriter& writer, const StreamedGraph::Costs& costs,
                         PassCounter& counter) {
  ChunkedAppender<Out> out(writer);
  costs.replay([&](std::uint64_t value) {
    out.push(static_cast<Out>(value));
    counter.tick();
  });
  out.flush();
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
          return narrowest_unsigned(
              values.empty() ? 0 : *std::max_element(values.begin(), values.end()));
        }
      },
      column.values);
}

void write_graph(const GraphInput& in, const std::filesystem::path& path, const Progress& progress,
                 std::string_view expect_digest) {
  check_input(in);
  const std::uint64_t n = in.vertex_count;
  const std::size_t m = in.tails.size();

  std::vector<ElementType> cost_types;
  for (const auto& c : in.costs) cost_types.push_back(choose_cost_type(c));
  const Metadata metadata = stored_metadata(in.metadata, in.costs, in.queries);
  const std::uint64_t section_total =
      6 + in.costs.size() + in.arc_data.size() + in.vertex_data.size() + in.queries.size();
  report(progress, "write", 0, section_total);

  // Counting sort by tail; iterating arcs in input order keeps it stable. The offsets have one
  // spare slot so that they serve as their own cursors: while arcs are placed, offsets[v + 1] is
  // the next free slot of tail v; afterwards it is the end of v's arcs, as the CSR wants.
  LargeArray<std::uint64_t> offsets(n + 2, 0);
  for (auto t : in.tails) ++offsets[t + 2];
  for (std::uint64_t v = 1; v <= n; ++v) offsets[v + 1] += offsets[v];
  LargeArray<std::uint32_t> order(m);  // order[p] = input index of CSR arc p
  for (std::uint32_t a = 0; a < m; ++a) order[offsets[in.tails[a] + 1]++] = a;
  offsets.pop_back();
  LargeArray<std::uint32_t> targets(m);
  for (std::size_t p = 0; p < m; ++p) targets[p] = in.heads[order[p]];

  // The transpose (derive_transpose, as unpacking derives it), built on a second core while the
  // forward sections are written and the costs gathered.
  LargeArray<std::uint64_t> reverse_offsets;
  LargeArray<std::uint32_t> reverse_sources, reverse_arcs;
  std::exception_ptr transpose_error;
  auto build_transpose = [&] {
    try {
      reverse_offsets.resize(n + 1);
      reverse_sources.resize(m);
      reverse_arcs.resize(m);
      if (!derive_transpose(offsets, targets, reverse_offsets.data(), reverse_sources.data(),
                            reverse_arcs.data()))
        throw Error("internal error: the built forward CSR is not one");
    } catch (...) {
      transpose_error = std::current_exception();
    }
  };
  std::jthread transpose;
  try {
    transpose = std::jthread(build_transpose);
  } catch (const std::system_error&) {  // no thread to be had (say, under an address-space limit)
    build_transpose();
  }

  FileWriter writer(path);
  writer.expect_digest(expect_digest);
  add_metadata_section(writer, metadata);
  writer.add_section(SectionKind::forward_offsets, "forward_offsets", 1,
                     std::span<const std::uint64_t>(offsets));
  writer.add_section(SectionKind::forward_targets, "forward_targets", 1,
                     std::span<const std::uint32_t>(targets));
  std::vector<LargeArray<std::byte>> cost_bytes;
  for (std::size_t i = 0; i < in.costs.size(); ++i)
    cost_bytes.push_back(
        std::visit([&](const auto& values) { return permuted_cost(cost_types[i], values, order); },
                   in.costs[i].values));
  if (transpose.joinable()) transpose.join();
  if (transpose_error) std::rethrow_exception(transpose_error);
  writer.add_section(SectionKind::reverse_offsets, "reverse_offsets", 1,
                     std::span<const std::uint64_t>(reverse_offsets));
  writer.add_section(SectionKind::reverse_sources, "reverse_sources", 1,
                     std::span<const std::uint32_t>(reverse_sources));
  writer.add_section(SectionKind::reverse_arcs, "reverse_arcs", 1,
                     std::span<const std::uint32_t>(reverse_arcs));
  for (std::size_t i = 0; i < in.costs.size(); ++i) {
    writer.begin_section(SectionKind::cost, in.costs[i].name, cost_types[i], 1);
    writer.append(cost_bytes[i]);
    writer.end_section();
    report(progress, "write", 6 + i + 1, section_total);
  }
  for (const auto& d : in.arc_data) {
    const std::size_t row_bytes = d.width * format::element_size(d.type);
    writer.begin_section(SectionKind::arc_data, d.name, d.type, d.width);
    for (auto index : order)
      writer.append(std::span(d.bytes).subspan(index * row_bytes, row_bytes));
    writer.end_section();
  }
  write_vertex_data(writer, in.vertex_data);
  add_query_sections(writer, in.queries);
  writer.commit(n, m);
  report(progress, "write", section_total, section_total);
}

namespace {

// The streamed instance's declared counts and in-memory columns, checked before any pass.
void check_streamed_input(const StreamedGraph& in) {
  check_counts(in.vertex_count, in.arc_count);
  check_unique_names("objective", in.costs);
  check_unique_names("vertex data", in.vertex_data);
  check_unique_names("arc data", in.arc_data);
  check_unique_names("query set", in.queries);
  for (const auto& d : in.vertex_data) check_rows(d, in.vertex_count, "vertex");
  for (const auto& d : in.arc_data) check_rows(d, in.arc_count, "arc");
  check_queries(in.queries, in.vertex_count);
}

// Pass 1: the forward offsets, counted from the tails. It is also the pass that checks the arcs
// (endpoints, tail order, count); the later passes rely on it.
void write_streamed_forward_offsets(FileWriter& writer, const StreamedGraph& in,
                                    PassCounter& counter) {
  const std::uint64_t n = in.vertex_count;
  const std::uint64_t m = in.arc_count;
  writer.begin_section(SectionKind::forward_offsets, "forward_offsets", ElementType::u64, 1);
  ChunkedAppender<std::uint64_t> out(writer);
  std::uint64_t arcs = 0, emitted = 0;  // offsets[v] = arcs with a tail below v
  in.replay_arcs([&](std::uint32_t tail, std::uint32_t head) {
    if (tail >= n || head >= n)
      throw Error("arc " + std::to_string(arcs) + " (" + std::to_string(tail) + " -> " +
                  std::to_string(head) + ") has an endpoint not below the vertex count " +
                  std::to_string(n));
    if (tail + std::uint64_t{1} < emitted)
      throw Error("internal error: streamed arc " + std::to_string(arcs) + " breaks tail order");
    if (arcs == m)
      throw Error("internal error: more streamed arcs than the " + std::to_string(m) + " declared");
    for (; emitted <= tail; ++emitted) out.push(arcs);
    ++arcs;
    counter.tick();
  });
  if (arcs != m)
    throw Error("internal error: " + std::to_string(arcs) + " streamed arcs, " + std::to_string(m) +
                " declared");
  for (; emitted <= n; ++emitted) out.push(arcs);
  out.flush();
  writer.end_section();
}

// Pass 2: the forward targets, the heads in arc order.
void write_streamed_forward_targets(FileWriter& writer, const StreamedGraph& in,
                                    PassCounter& counter) {
  writer.begin_section(SectionKind::forward_targets, "forward_targets", ElementType::u32, 1);
  ChunkedAppender<std::uint32_t> out(writer);
  in.replay_arcs([&](std::uint32_t, std::uint32_t head) {
    out.push(head);
    counter.tick();
  });
  out.flush();
  writer.end_section();
}

// Passes 3 and 4: the transpose, as write_graph builds it: forward arcs in id order keep each
// in-list ascending. The only arrays held in memory: 8 (n + 1) + 8 m bytes.
void write_streamed_transpose(FileWriter& writer, const StreamedGraph& in, PassCounter& counter) {
  const std::uint64_t n = in.vertex_count;
  const std::uint64_t m = in.arc_count;
  LargeArray<std::uint64_t> reverse_offsets(n + 1, 0);
  in.replay_arcs([&](std::uint32_t, std::uint32_t head) {
    ++reverse_offsets[head + 1];
    counter.tick();
  });
  for (std::uint64_t v = 0; v < n; ++v) reverse_offsets[v + 1] += reverse_offsets[v];
  writer.add_section(SectionKind::reverse_offsets, "reverse_offsets", 1,
                     std::span<const std::uint64_t>(reverse_offsets));
  LargeArray<std::uint32_t> reverse_sources(m), reverse_arcs(m);
  auto& cursor = reverse_offsets;  // written already: reused as the next free slot per head
  std::uint32_t arc = 0;
  in.replay_arcs([&](std::uint32_t tail, std::uint32_t head) {
    const auto slot = cursor[head]++;
    reverse_sources[slot] = tail;
    reverse_arcs[slot] = arc++;
    counter.tick();
  });
  writer.add_section(SectionKind::reverse_sources, "reverse_sources", 1,
                     std::span<const std::uint32_t>(reverse_sources));
  writer.add_section(SectionKind::reverse_arcs, "reverse_arcs", 1,
                     std::span<const std::uint32_t>(reverse_arcs));
}

// Two passes per objective: one finds the narrowest type that holds its largest cost, the other
// writes the costs in it.
void write_streamed_costs(FileWriter& writer, const StreamedGraph& in, PassCounter& counter) {
  const std::uint64_t m = in.arc_count;
  for (const auto& costs : in.costs) {
    std::uint64_t max = 0, count = 0;
    costs.replay([&](std::uint64_t value) {
      max = std::max(max, value);
      ++count;
      counter.tick();
    });
    if (count != m)
      throw Error("objective '" + costs.name + "' has " + std::to_string(count) + " costs for " +
                  std::to_string(m) + " arcs");
    const auto type = narrowest_unsigned(max);
    writer.begin_section(SectionKind::cost, costs.name, type, 1);
    switch (type) {
      case ElementType::u8:
        write_streamed_cost<std::uint8_t>(writer, costs, counter);
        break;
      case ElementType::u16:
        write_streamed_cost<std::uint16_t>(writer, costs, counter);
        break;
      case ElementType::u32:
        write_streamed_cost<std::uint32_t>(writer, costs, counter);
        break;
      default:
        write_streamed_cost<std::uint64_t>(writer, costs, counter);
        break;
    }
    writer.end_section();
  }
}

}  // namespace

void write_graph(const StreamedGraph& in, const std::filesystem::path& path,
                 const Progress& progress, std::string_view expect_digest) {
  const std::uint64_t n = in.vertex_count;
  const std::uint64_t m = in.arc_count;
  check_streamed_input(in);
  const Metadata metadata = stored_metadata(in.metadata, in.costs, in.queries);
  PassCounter counter(progress, m * (4 + 2 * in.costs.size()));

  // Every pass sees the same arcs: the first checks them, the others rely on that.
  FileWriter writer(path);
  writer.expect_digest(expect_digest);
  add_metadata_section(writer, metadata);
  write_streamed_forward_offsets(writer, in, counter);
  write_streamed_forward_targets(writer, in, counter);
  write_streamed_transpose(writer, in, counter);
  write_streamed_costs(writer, in, counter);
  for (const auto& d : in.arc_data) {  // already in arc order: the arcs come in tail order
    writer.begin_section(SectionKind::arc_data, d.name, d.type, d.width);
    writer.append(std::span(d.bytes));
    writer.end_section();
  }
  write_vertex_data(writer, in.vertex_data);
  add_query_sections(writer, in.queries);
  writer.commit(n, m);
  counter.finish();
}

GraphInput materialize(const StreamedGraph& in) {
  GraphInput out;
  out.vertex_count = in.vertex_count;
  out.tails.reserve(in.arc_count);
  out.heads.reserve(in.arc_count);
  in.replay_arcs([&](std::uint32_t tail, std::uint32_t head) {
    out.tails.push_back(tail);
    out.heads.push_back(head);
  });
  for (const auto& costs : in.costs) {
    std::vector<std::uint64_t> values;
    values.reserve(in.arc_count);
    costs.replay([&](std::uint64_t value) { values.push_back(value); });
    out.costs.push_back({costs.name, costs.unit, std::move(values), std::nullopt});
  }
  out.arc_data = in.arc_data;
  out.vertex_data = in.vertex_data;
  out.queries = in.queries;
  out.metadata = in.metadata;
  return out;
}

void write_query_set(FileWriter& writer, const QuerySet& set) {
  writer.begin_section(SectionKind::queries, set.name, ElementType::u32, 2);
  writer.append(std::as_bytes(std::span(set.pairs)));
  writer.end_section();
  if (set.reference)
    writer.add_section(SectionKind::query_reference, set.name, 1,
                       std::span<const double>(set.reference->values));
}

void add_reference_metadata(Metadata& metadata, const QuerySet& set,
                            const std::vector<std::string>& objectives, const std::string& what) {
  if (!set.reference) return;
  const auto& r = *set.reference;
  const std::string label = what + "query set '" + set.name + "': reference";
  if (r.values.size() != set.pairs.size())
    throw Error(label + " has " + std::to_string(r.values.size()) + " values for " +
                std::to_string(set.pairs.size()) + " queries");
  if (std::find(objectives.begin(), objectives.end(), r.objective) == objectives.end())
    throw Error(label + " names objective '" + r.objective + "', which is no cost section");
  for (std::size_t i = 0; i < r.values.size(); ++i)
    if (!std::isfinite(r.values[i]) || r.values[i] < 0)
      throw Error(label + ", query " + std::to_string(i) + ": " + std::to_string(r.values[i]) +
                  " is not a finite number >= 0");
  const std::string key = "queries." + set.name + ".reference.";
  metadata.set(key + "objective", r.objective);
  metadata.set(key + "source", r.source);
}

}  // namespace mosb
