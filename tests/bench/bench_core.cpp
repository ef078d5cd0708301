// mosb_bench_core: the core figures of the format on two instances of benchmark size.
//
//   mosb_bench_core [--dir DIR] [--quick]
//
// For (a) Grid 600x600 with 3 objectives (converters::generate_grid, seed 1) and (b) a random graph
// of DIMACS-FLA size (1,070,376 vertices, 2,712,798 arcs, 2 objectives), it prints: the time to
// write the file and its size; the time to open it and to reach its first arc; the time to sum
// every cost through the public API; and the throughput of verify (checksums / structure / full)
// beside a plain memory read of the same mapping. It checks every result and exits 1 on a wrong
// one, but it never fails because the machine is slow: it has no time limits. Not registered with
// ctest. BENCHMARKS.md has the commands and the figures of a reference run.

#include <sys/mman.h>
#include <unistd.h>
#include <xxhash.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <filesystem>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <thread>
#include <vector>

#include "mosb/converters/grid_generator.hpp"
#include "mosb/error.hpp"
#include "mosb/graph_builder.hpp"
#include "mosb/graph_reader.hpp"
#include "mosb/random.hpp"
#include "mosb/verify.hpp"

namespace {

using Clock = std::chrono::steady_clock;
using mosb::GraphInput;
using mosb::GraphReader;
using mosb::VerifyLevel;
using mosb::format::ElementType;

// Every computed value ends up here (and most are printed too), so no pass can be optimised away.
volatile std::uint64_t g_sink = 0;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

[[noreturn]] void die(const std::string& what) {
  std::fflush(stdout);
  std::fprintf(stderr, "mosb_bench_core: FAILED: %s\n", what.c_str());
  std::exit(1);
}

void check(bool ok, const std::string& what) {
  if (!ok) die(what);
}

// 1070376 -> "1,070,376"
std::string grouped(std::uint64_t value) {
  std::string digits = std::to_string(value), out;
  for (std::size_t i = 0; i < digits.size(); ++i) {
    if (i > 0 && (digits.size() - i) % 3 == 0) out += ',';
    out += digits[i];
  }
  return out;
}

std::string format(const char* pattern, double value) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, pattern, value);
  return buffer;
}

// One "label  value" row of an instance's table.
void row(std::string_view label, const std::string& value) {
  std::printf("  %-38.*s %s\n", static_cast<int>(label.size()), label.data(), value.c_str());
}

struct Stats {
  double min = 0, p10 = 0, median = 0, p90 = 0, max = 0;
};

Stats stats_of(std::vector<double> samples) {
  std::sort(samples.begin(), samples.end());
  auto at = [&](double q) {
    return samples[static_cast<std::size_t>(q * (samples.size() - 1) + 0.5)];
  };
  return {samples.front(), at(0.10), at(0.50), at(0.90), samples.back()};
}

// ---------------------------------------------------------------------------------------------
// Instance (b): a random graph of DIMACS-FLA size.
//
// Model (deterministic: SplitMix64 streams of seed 1; the exact model does not matter, only that
// the file has the size and rough shape of a road graph):
//  * n vertices on a jittered W x W lattice, W = ceil(sqrt(n)): vertex v sits at column v % W,
//    row v / W, 1000 m apart, each coordinate moved by a uniform jitter in [-300, 300] m. The
//    coordinates are stored as vertex data `coords` (i32 x 2), as a DIMACS conversion would.
//  * Roads are undirected and stored as two arcs u->v, v->u with the same costs, as in the DIMACS
//    road graphs, so m/2 edges:
//      - the chain v -- v+1 for v = 0 .. n-2 (every vertex gets its east neighbour; the edge at the
//        end of a lattice row runs back to the start of the next row: a long "highway");
//      - the other m/2 - (n-1) edges join a uniform random vertex u to a north or diagonal
//        neighbour u + W + delta, delta uniform in {-1, 0, 1} (u - W - delta in the last row).
//  * distance = round(euclidean metres x detour), detour uniform in [1.00, 1.50], clamped to
//    [1, 100000]; time = ceil(distance x 36 / speed) in tenths of a second, speed uniform in
//    {30, 50, 70, 90, 110} km/h: correlated with distance, like the DIMACS distance/time pair.
//    Both columns end up u32 (their maxima exceed 65535).
//  * 100 random (start, goal) queries in the set `default`, view `FLA` = distance,time.
// ---------------------------------------------------------------------------------------------
GraphInput make_road_like(std::uint64_t n, std::uint64_t m) {
  check(m % 2 == 0 && m / 2 >= n - 1, "road-like model needs an even m >= 2(n-1)");
  const auto width = static_cast<std::uint64_t>(std::ceil(std::sqrt(static_cast<double>(n))));
  check(n > 2 * width + 2, "road-like model needs at least a few lattice rows");

  GraphInput g;
  g.vertex_count = n;
  std::vector<std::int32_t> coords(2 * n);
  {
    auto rng = mosb::stream(1, 0);
    for (std::uint64_t v = 0; v < n; ++v) {
      coords[2 * v] = static_cast<std::int32_t>((v % width) * 1000 + rng.uniform(0, 600)) - 300;
      coords[2 * v + 1] = static_cast<std::int32_t>((v / width) * 1000 + rng.uniform(0, 600)) - 300;
    }
  }
  g.tails.reserve(m);
  g.heads.reserve(m);
  std::vector<std::uint64_t> distance, time;
  distance.reserve(m);
  time.reserve(m);
  auto cost_rng = mosb::stream(1, 2);
  auto edge = [&](std::uint64_t u, std::uint64_t v) {
    const double dx = coords[2 * u] - coords[2 * v], dy = coords[2 * u + 1] - coords[2 * v + 1];
    const double detour = 1.0 + static_cast<double>(cost_rng.uniform(0, 500)) / 1000.0;
    const auto d = static_cast<std::uint64_t>(
        std::clamp(std::round(std::sqrt(dx * dx + dy * dy) * detour), 1.0, 100000.0));
    static constexpr std::uint64_t kSpeeds[] = {30, 50, 70, 90, 110};
    const std::uint64_t speed = kSpeeds[cost_rng.uniform(0, 4)];
    const std::uint64_t t = (d * 36 + speed - 1) / speed;
    for (auto [a, b] : {std::pair{u, v}, std::pair{v, u}}) {
      g.tails.push_back(static_cast<std::uint32_t>(a));
      g.heads.push_back(static_cast<std::uint32_t>(b));
      distance.push_back(d);
      time.push_back(t);
    }
  };
  for (std::uint64_t v = 0; v + 1 < n; ++v) edge(v, v + 1);
  auto edge_rng = mosb::stream(1, 1);
  for (std::uint64_t e = n - 1; e < m / 2; ++e) {
    const std::uint64_t u = edge_rng.uniform(0, n - 1);
    const std::uint64_t step = width - 1 + edge_rng.uniform(0, 2);  // W + delta, delta in {-1,0,1}
    edge(u, u + step < n ? u + step : u - step);
  }
  check(g.tails.size() == m,
        "road-like model produced " + std::to_string(g.tails.size()) + " arcs");

  g.costs.push_back({"distance", "m", std::move(distance), std::nullopt});
  g.costs.push_back({"time", "0.1 s", std::move(time), std::nullopt});
  g.vertex_data.push_back(mosb::DataColumn::from("coords", 2, coords));
  mosb::QuerySet queries{"default", {}};
  auto query_rng = mosb::stream(1, 3);
  for (int i = 0; i < 100; ++i)
    queries.pairs.push_back({static_cast<std::uint32_t>(query_rng.uniform(0, n - 1)),
                             static_cast<std::uint32_t>(query_rng.uniform(0, n - 1))});
  g.queries.push_back(std::move(queries));
  g.metadata.set("benchmark", "bench-FLA-size");
  g.metadata.set("family", "road");
  g.metadata.set("id_base", "0");
  g.metadata.set("source.command", "mosb_bench_core road-like");
  g.metadata.set("source.param.seed", "1");
  g.metadata.set("view.FLA.objectives", "distance,time");
  g.metadata.set("view.FLA.queries", "default");
  return g;
}

// ---------------------------------------------------------------------------------------------
// Reading through the public API.

// Calls f(span<const T>) with objective i in its stored type.
template <class F>
void with_cost(const GraphReader& reader, std::size_t i, F&& f) {
  switch (reader.objective(i).type) {
    case ElementType::u8:
      return f(reader.cost<std::uint8_t>(i));
    case ElementType::u16:
      return f(reader.cost<std::uint16_t>(i));
    case ElementType::u32:
      return f(reader.cost<std::uint32_t>(i));
    case ElementType::u64:
      return f(reader.cost<std::uint64_t>(i));
    case ElementType::f32:
      return f(reader.cost<float>(i));
    case ElementType::f64:
      return f(reader.cost<double>(i));
    default:
      die("objective " + std::to_string(i) + " has a type a cost column cannot have");
  }
}

// Integer columns sum exactly in u64; float columns in double (compared with a tolerance, since
// the file holds the arcs in CSR order, not in input order).
struct ColumnSum {
  bool real = false;
  std::uint64_t integer = 0;
  double value = 0;
  std::string text() const { return real ? format("%.6g", value) : grouped(integer); }
  bool matches(const ColumnSum& o) const {
    if (real != o.real) return false;
    if (!real) return integer == o.integer;
    return std::abs(value - o.value) <= 1e-9 * std::max(1.0, std::abs(o.value));
  }
};

template <class T>
ColumnSum sum_span(std::span<const T> values) {
  ColumnSum s;
  if constexpr (std::is_floating_point_v<T>) {
    s.real = true;
    double total = 0;
    for (T x : values) total += x;
    s.value = total;
  } else {
    std::uint64_t total = 0;
    for (T x : values) total += x;
    s.integer = total;
  }
  return s;
}

std::vector<ColumnSum> sum_all_costs(const GraphReader& reader) {
  std::vector<ColumnSum> sums;
  for (std::size_t i = 0; i < reader.objective_count(); ++i)
    with_cost(reader, i, [&](auto span) { sums.push_back(sum_span(span)); });
  return sums;
}

// The plain memory-read baseline: every byte of the file, as u64 words.
std::uint64_t sum_words(std::span<const std::byte> bytes) {
  const std::size_t words = bytes.size() / 8;
  const std::byte* p = bytes.data();
  std::uint64_t total = 0;
  for (std::size_t i = 0; i < words; ++i) {
    std::uint64_t w;
    std::memcpy(&w, p + 8 * i, 8);
    total += w;
  }
  for (std::size_t i = words * 8; i < bytes.size(); ++i) total += static_cast<std::uint64_t>(p[i]);
  return total;
}

// Fraction of the mapping's pages that are in the page cache (mincore).
double resident_fraction(std::span<const std::byte> bytes) {
  const auto page = static_cast<std::size_t>(::sysconf(_SC_PAGESIZE));
  const std::size_t pages = (bytes.size() + page - 1) / page;
  std::vector<unsigned char> flags(pages);
  if (::mincore(const_cast<std::byte*>(bytes.data()), bytes.size(), flags.data()) != 0) return -1;
  std::size_t resident = 0;
  for (auto f : flags) resident += f & 1;
  return static_cast<double>(resident) / static_cast<double>(pages);
}

// ---------------------------------------------------------------------------------------------

struct Options {
  std::filesystem::path dir = "/tmp/mosb-bench";
  bool quick = false;
};

struct Sizes {
  int open_repetitions;
  int pass_repetitions;
};

struct Expected {
  std::uint64_t n = 0, m = 0;
  std::vector<ColumnSum> sums;
  std::uint64_t first_offset_end = 0;  // forward_offsets()[1]
  std::uint32_t first_target = 0;      // forward_targets()[0]
  ColumnSum first_cost;                // objective 0 of arc 0
};

// What the file must contain, from the input: the CSR is stable by tail, so arc 0 is the first
// input arc of the smallest tail.
Expected expected_of(const GraphInput& g) {
  Expected e;
  e.n = g.vertex_count;
  e.m = g.tails.size();
  for (const auto& c : g.costs)
    e.sums.push_back(std::visit(
        [](const auto& v) { return sum_span(std::span(v.data(), v.size())); }, c.values));
  const auto min_tail = *std::min_element(g.tails.begin(), g.tails.end());
  const auto first = static_cast<std::size_t>(std::find(g.tails.begin(), g.tails.end(), min_tail) -
                                              g.tails.begin());
  e.first_offset_end =
      min_tail == 0 ? static_cast<std::uint64_t>(std::count(g.tails.begin(), g.tails.end(), 0u))
                    : 0;
  e.first_target = g.heads[first];
  e.first_cost = std::visit([&](const auto& v) { return sum_span(std::span(v.data() + first, 1)); },
                            g.costs[0].values);
  return e;
}

struct Result {
  std::string name;
  std::uint64_t file_size = 0;
  double open_median_us = 0;
  double first_arc_median_us = 0;
  double baseline_s = 0, checksums_s = 0, full_s = 0;
  double fresh_baseline_s = 0, fresh_full_s = 0;
};

Result run_instance(const std::string& name, const std::function<GraphInput()>& make,
                    const std::filesystem::path& path, const Sizes& sizes) {
  Result result;
  result.name = name;
  std::printf("\n== %s ==\n", name.c_str());

  // Generate and write.
  Expected expected;
  double generate_s = 0, write_s = 0;
  {
    auto start = Clock::now();
    GraphInput input = make();
    generate_s = seconds_since(start);
    expected = expected_of(input);
    std::error_code ignored;
    std::filesystem::remove(path, ignored);
    start = Clock::now();
    mosb::write_graph(input, path);
    write_s = seconds_since(start);
  }  // the input is freed here: the rest measures the file only
  const std::uint64_t file_size = std::filesystem::file_size(path);
  result.file_size = file_size;

  GraphReader reader = GraphReader::open(path);
  check(reader.vertex_count() == expected.n && reader.arc_count() == expected.m,
        name + ": the file has other vertex or arc counts than the input");
  check(reader.header().file_size == file_size, name + ": header file_size differs from the file");
  check(reader.objective_count() == expected.sums.size(), name + ": objective count differs");
  std::uint64_t cost_bytes = 0;
  std::string cost_types;
  for (std::size_t i = 0; i < reader.objective_count(); ++i) {
    const auto& s = reader.objective(i);
    cost_bytes += s.stored.size();
    cost_types += (i ? ", " : "") + s.name + " " + std::string(mosb::format::to_string(s.type));
  }

  row("file", path.string());
  row("vertices / arcs / objectives", grouped(expected.n) + " / " + grouped(expected.m) + " / " +
                                          std::to_string(expected.sums.size()));
  row("sections", std::to_string(reader.sections().size()) + " (cost columns: " + cost_types + ")");
  row("generate input in memory", format("%.3f s", generate_s));
  row("write_graph (CSR, checksums, fsync)",
      format("%.3f s", write_s) + "  (" + format("%.0f MB/s", file_size / write_s / 1e6) + ")");
  row("file size", grouped(file_size) + " bytes = " + format("%.1f MB", file_size / 1e6) + ", " +
                       format("%.2f bytes/arc", static_cast<double>(file_size) / expected.m) +
                       " (costs: " + format("%.1f MB", cost_bytes / 1e6) + ")");

  // Warm: read every byte once through this mapping. The file was just written, so it should be in
  // the page cache already; mincore says how much of it is.
  g_sink = g_sink + sum_words(reader.bytes());
  const double resident = resident_fraction(reader.bytes());
  row("page cache residency after warm-up",
      resident < 0 ? "unknown (mincore failed)" : format("%.1f %%", 100 * resident));

  // Open: median of many repetitions. The reader is destroyed (munmap) outside the timed region.
  {
    std::vector<double> open_us, first_us;
    for (int r = 0; r < sizes.open_repetitions; ++r) {
      const auto start = Clock::now();
      GraphReader fresh = GraphReader::open(path);
      open_us.push_back(seconds_since(start) * 1e6);
      g_sink = g_sink + fresh.sections().size();
    }
    for (int r = 0; r < sizes.open_repetitions; ++r) {
      const auto start = Clock::now();
      GraphReader fresh = GraphReader::open(path);
      const auto offsets = fresh.forward_offsets();
      const std::uint64_t begin = offsets[0], end = offsets[1];
      const std::uint32_t target = fresh.forward_targets()[0];
      ColumnSum cost;
      with_cost(fresh, 0, [&](auto span) { cost = sum_span(span.first(1)); });
      first_us.push_back(seconds_since(start) * 1e6);
      check(begin == 0 && end == expected.first_offset_end && target == expected.first_target &&
                cost.matches(expected.first_cost),
            name + ": the first arc read back differs from the input");
      g_sink = g_sink + end + target + cost.integer;
    }
    const Stats open = stats_of(open_us), first = stats_of(first_us);
    result.open_median_us = open.median;
    result.first_arc_median_us = first.median;
    auto line = [](const Stats& s) {
      return format("median %7.1f us", s.median) + format("  (p10 %.1f", s.p10) +
             format(", p90 %.1f", s.p90) + format(", min %.1f us)", s.min);
    };
    row("open (" + std::to_string(sizes.open_repetitions) + " runs)", line(open));
    row("open + reach first arc and cost", line(first));
  }

  // Sum every cost through cost<T>(i), each run on a fresh mapping (so it includes the minor
  // page faults of mapping page-cache pages), timing the sums only.
  {
    std::vector<double> times;
    std::vector<ColumnSum> sums;
    for (int r = 0; r < sizes.pass_repetitions; ++r) {
      GraphReader fresh = GraphReader::open(path);
      const auto start = Clock::now();
      sums = sum_all_costs(fresh);
      times.push_back(seconds_since(start));
      check(sums.size() == expected.sums.size(), name + ": wrong number of cost sums");
      for (std::size_t i = 0; i < sums.size(); ++i)
        check(sums[i].matches(expected.sums[i]), name + ": objective " + std::to_string(i) +
                                                     " sums to " + sums[i].text() +
                                                     ", the input to " + expected.sums[i].text());
      g_sink = g_sink + sums[0].integer;
    }
    const Stats s = stats_of(times);
    std::string listed;
    for (std::size_t i = 0; i < sums.size(); ++i)
      listed += (i ? ", " : "") + reader.objective(i).name + " " + sums[i].text();
    row("sum all costs, fresh mapping (best)",
        format("%.2f ms", s.min * 1e3) + format(" = %.2f GB/s", cost_bytes / s.min / 1e9) +
            format("  (median %.2f ms)", s.median * 1e3));
    row("  sums (checked against the input)", listed);
  }

  // Whole-file passes. "mapped" rows reuse `reader`, whose every page was touched above: no page
  // faults, no I/O. "fresh" rows open a new mapping per run: minor faults, no I/O. Runs of the
  // different passes are interleaved and the best of each is kept.
  struct Pass {
    const char* label;
    bool fresh;
    std::function<std::uint64_t(const GraphReader&)> run;
    double best = 1e30;
    std::uint64_t value = 0;
  };
  auto verify_pass = [name](VerifyLevel level) {
    return [name, level](const GraphReader& r) -> std::uint64_t {
      if (auto problem = mosb::verify(r, level)) die(name + ": verify: " + *problem);
      return 1;
    };
  };
  const auto words = [](const GraphReader& r) { return sum_words(r.bytes()); };
  std::vector<Pass> passes = {
      {"plain read (sum of u64 words)", false, words},
      {"XXH3-64 of the whole file", false,
       [](const GraphReader& r) { return XXH3_64bits(r.bytes().data(), r.bytes().size()); }},
      {"verify checksums", false, verify_pass(VerifyLevel::checksums)},
      {"verify structure", false, verify_pass(VerifyLevel::structure)},
      {"verify full", false, verify_pass(VerifyLevel::full)},
      {"plain read, fresh mapping", true, words},
      {"verify full, fresh mapping", true, verify_pass(VerifyLevel::full)},
  };
  for (int r = 0; r < sizes.pass_repetitions; ++r)
    for (auto& pass : passes) {
      std::optional<GraphReader> fresh;
      if (pass.fresh) fresh.emplace(GraphReader::open(path));
      const GraphReader& target = pass.fresh ? *fresh : reader;
      const auto start = Clock::now();
      const std::uint64_t value = pass.run(target);
      pass.best = std::min(pass.best, seconds_since(start));
      check(r == 0 || value == pass.value, name + ": " + pass.label + " gave different results");
      pass.value = value;
      g_sink = g_sink + value;
    }
  check(passes[0].value == passes[5].value, name + ": the two plain reads disagree");

  const std::string heading = "whole-file pass, best of " + std::to_string(sizes.pass_repetitions);
  std::printf("\n  %-38s %10s %9s %12s\n", heading.c_str(), "time", "GB/s", "x baseline");
  for (const auto& pass : passes) {
    const double baseline = pass.fresh ? passes[5].best : passes[0].best;
    std::printf("  %-38s %7.2f ms %9.2f %11.2fx\n", pass.label, pass.best * 1e3,
                file_size / pass.best / 1e9, pass.best / baseline);
  }
  std::printf(
      "  (x baseline = time / the plain read on the same kind of mapping; GB/s over the\n"
      "   file size; plain-read word sum %016llx, XXH3-64 %016llx)\n",
      static_cast<unsigned long long>(passes[0].value),
      static_cast<unsigned long long>(passes[1].value));
  result.baseline_s = passes[0].best;
  result.checksums_s = passes[2].best;
  result.full_s = passes[4].best;
  result.fresh_baseline_s = passes[5].best;
  result.fresh_full_s = passes[6].best;
  return result;
}

// mosb::verify spreads its work over hardware_concurrency threads (files of 1 MB and more).
unsigned verify_threads() {
  return std::max(1u, std::thread::hardware_concurrency());
}

void print_targets(const std::vector<Result>& results) {
  std::printf("\n== targets ==\n");
  auto verdict = [](bool met) { return met ? "met" : "MISSED"; };
  for (const auto& r : results) {
    std::printf("  %s (%s MB)\n", r.name.c_str(), format("%.1f", r.file_size / 1e6).c_str());
    std::printf("    %-66s %s\n",
                ("open in microseconds: median " + format("%.1f us", r.open_median_us) +
                 ", first arc " + format("%.1f us", r.first_arc_median_us))
                    .c_str(),
                verdict(r.open_median_us < 1000 && r.first_arc_median_us < 1000));
    const double ratio = r.full_s / r.baseline_s;
    std::printf("    %-66s %s\n",
                ("verify full within 2x of plain read: " + format("%.2fx", ratio) +
                 format(" (checksums %.2fx)", r.checksums_s / r.baseline_s))
                    .c_str(),
                verdict(ratio <= 2.0));
    const double gbps = r.file_size / r.full_s / 1e9 / verify_threads();
    std::printf("    %-66s %s\n",
                ("verify full >= 5 GB/s per core: " + format("%.2f GB/s", gbps) +
                 format(" (checksums %.2f GB/s)", r.file_size / r.checksums_s / 1e9))
                    .c_str(),
                verdict(gbps >= 5.0));
  }
  if (results.size() >= 2)
    std::printf("  open time ratio, largest / smallest file: %.2f (file size ratio %.2f)\n",
                results.back().open_median_us / results.front().open_median_us,
                static_cast<double>(results.back().file_size) / results.front().file_size);
  std::printf(
      "  (verify runs on %u threads, so its GB/s per core is the total / %u; the plain read\n"
      "   runs on one)\n",
      verify_threads(), verify_threads());
}

}  // namespace

int main(int argc, char** argv) {
  Options options;
  for (int i = 1; i < argc; ++i) {
    const std::string_view arg = argv[i];
    if (arg == "--quick") {
      options.quick = true;
    } else if (arg == "--dir" && i + 1 < argc) {
      options.dir = argv[++i];
    } else if (arg == "--help" || arg == "-h") {
      std::printf(
          "usage: %s [--dir DIR] [--quick]\n"
          "  --dir DIR  where to write the instance files (default /tmp/mosb-bench)\n"
          "  --quick    small instances and few repetitions: a smoke run\n",
          argv[0]);
      return 0;
    } else {
      std::fprintf(stderr, "usage: %s [--dir DIR] [--quick]\n", argv[0]);
      return 2;
    }
  }
  const Sizes sizes = options.quick ? Sizes{200, 3} : Sizes{1000, 5};
  const std::uint32_t grid_side = options.quick ? 60 : 600;
  const std::uint64_t road_n = options.quick ? 107037 : 1070376;
  const std::uint64_t road_m = options.quick ? 271280 : 2712798;

  try {
    std::filesystem::create_directories(options.dir);
    std::printf("mosb_bench_core%s\n", options.quick ? " --quick (smoke run: small sizes)" : "");
    std::printf("  cores (hardware_concurrency)   %u\n", std::thread::hardware_concurrency());
    std::printf("  compiler                       %s (%s)\n", MOSB_BENCH_COMPILER, __VERSION__);
    std::printf(
        "  build type / flags             %s: %s -std=c++20, no -march (library and benchmark\n"
        "                                 alike; plus warning flags); XXH3 from the system "
        "libxxhash\n",
        MOSB_BENCH_BUILD_TYPE, MOSB_BENCH_CXX_FLAGS);
    std::printf("  libxxhash                      %u.%u.%u\n", XXH_versionNumber() / 10000,
                XXH_versionNumber() / 100 % 100, XXH_versionNumber() % 100);
    std::printf("  instance directory             %s (files are left there)\n",
                options.dir.string().c_str());
    std::printf(
        "  warm = the file is in the OS page cache (it was just written, then read once in full\n"
        "         through the mapping), so nothing touches the disk. 'mapped' passes reuse that\n"
        "         mapping (no page faults); 'fresh mapping' passes open a new one per run and so\n"
        "         include minor page faults. Timings are std::chrono::steady_clock. The plain "
        "read\n"
        "         and XXH3 rows run on one thread; verify uses every core "
        "(hardware_concurrency).\n");

    std::vector<Result> results;
    const std::string grid_name = "Grid " + std::to_string(grid_side) + "x" +
                                  std::to_string(grid_side) + ", 3 objectives, seed 1";
    results.push_back(run_instance(
        grid_name,
        [&] {
          mosb::converters::GridParameters p;
          p.width = p.height = grid_side;
          p.objectives = 3;
          p.seed = 1;
          return mosb::converters::generate_grid(p);
        },
        options.dir / ("grid-" + std::to_string(grid_side) + ".mosb"), sizes));
    results.push_back(run_instance(
        "road-like random graph of DIMACS-FLA size (" + grouped(road_n) + " vertices, " +
            grouped(road_m) + " arcs, 2 objectives)",
        [&] { return make_road_like(road_n, road_m); },
        options.dir / (options.quick ? "road-like-small.mosb" : "road-like-fla.mosb"), sizes));
    print_targets(results);
  } catch (const std::exception& e) {
    die(e.what());
  }
  return 0;
}
