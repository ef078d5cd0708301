// libFuzzer target: arbitrary bytes as two fronts (a solver's and a reference's) of integer, f64
// or f32 costs, through evaluate_front (spec/EVALUATION.md): every call must return (the
// achieved-ε search once stepped an ulp of ε at a time and hung on values an ulp apart), and its
// answers must agree with the definition, checked by brute force: the solution covers the
// reference at the achieved ε and, for doubles, not at the ε of the double below 1 + it; a
// requested ε covers exactly when it is at least the achieved one (for doubles: when 1 + ε,
// rounded, is). Any other outcome than a clean mosb::Error aborts.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <vector>

#include "mosb/error.hpp"
#include "mosb/eval.hpp"

namespace {

constexpr std::size_t kMaxVectors = 64;  // the brute-force check is quadratic

void check(bool condition) {
  if (!condition) std::abort();
}

// The coverage test of spec/EVALUATION.md §2 for doubles, from the definition.
bool covers(const double* p, const double* q, std::size_t d, double e) {
  for (std::size_t i = 0; i < d; ++i)
    if (!(std::isinf(e) ? (q[i] > 0 || p[i] == 0) : p[i] <= (1.0 + e) * q[i])) return false;
  return true;
}

bool all_covered(const std::vector<double>& s, const std::vector<double>& r, std::size_t d,
                 double e) {
  for (std::size_t b = 0; b < r.size() / d; ++b) {
    bool covered = false;
    for (std::size_t a = 0; a < s.size() / d && !covered; ++a)
      covered = covers(&s[a * d], &r[b * d], d, e);
    if (!covered) return false;
  }
  return true;
}

// Costs as the files hold them: finite and >= 0 (a negative value is mirrored, a non-finite one
// becomes 0); f32 costs widened from a float.
std::vector<double> doubles(const std::uint8_t* data, std::size_t size, bool f32) {
  std::vector<double> values;
  const std::size_t width = f32 ? 4 : 8;
  for (std::size_t at = 0; at + width <= size; at += width) {
    double v = 0;
    if (f32) {
      float f = 0;
      std::memcpy(&f, data + at, 4);
      v = f;
    } else {
      std::memcpy(&v, data + at, 8);
    }
    values.push_back(std::isfinite(v) ? std::fabs(v) : 0.0);
  }
  return values;
}

void fuzz_double(const std::vector<double>& values, std::size_t d, std::size_t split,
                 const std::vector<mosb::Ratio>& eps, const mosb::EvalOptions& options) {
  const std::size_t vectors = std::min(values.size() / d, 2 * kMaxVectors);
  const std::size_t n = std::min(vectors * split / 256, kMaxVectors);
  const std::size_t m = std::min(vectors - n, kMaxVectors);
  const std::vector<double> s(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(n * d));
  const std::vector<double> r(values.begin() + static_cast<std::ptrdiff_t>(n * d),
                              values.begin() + static_cast<std::ptrdiff_t>((n + m) * d));
  const auto result = mosb::evaluate_front(mosb::FrontView<double>{s, d},
                                           mosb::FrontView<double>{r, d}, eps, options);
  // Covered at ε exactly when fl(1+ε) ≥ 1 + the achieved ε (infinite: no ε covers).
  const double achieved = result.achieved_value;
  check(achieved >= 0);
  if (!std::isinf(achieved)) check(all_covered(s, r, d, achieved));
  if (achieved > 0) check(!all_covered(s, r, d, std::nextafter(1 + achieved, 0.0) - 1));
  for (std::size_t k = 0; k < eps.size(); ++k) {
    const auto& c = result.coverage.at(k);
    check(c.covered == (c.uncovered == 0 && c.extra == 0));
    if (eps[k].num != 0 && !options.strict_dominance)
      check(c.covered == (1 + eps[k].to_double() >= 1 + achieved));
  }
}

void fuzz_integer(const std::uint8_t* data, std::size_t size, std::size_t d, std::size_t split,
                  const std::vector<mosb::Ratio>& eps, const mosb::EvalOptions& options) {
  std::vector<std::uint64_t> values;
  for (std::size_t at = 0; at + 8 <= size; at += 8) {
    std::uint64_t v = 0;
    std::memcpy(&v, data + at, 8);
    values.push_back(v % 3 == 0 ? v % 16 : v >> 11);  // small values (ties, zeros) and up to 2^53
  }
  const std::size_t vectors = std::min(values.size() / d, 2 * kMaxVectors);
  const std::size_t n = std::min(vectors * split / 256, kMaxVectors);
  const std::size_t m = std::min(vectors - n, kMaxVectors);
  const std::vector<std::uint64_t> s(values.begin(),
                                     values.begin() + static_cast<std::ptrdiff_t>(n * d));
  const std::vector<std::uint64_t> r(values.begin() + static_cast<std::ptrdiff_t>(n * d),
                                     values.begin() + static_cast<std::ptrdiff_t>((n + m) * d));
  const mosb::FrontView<std::uint64_t> sv{s, d}, rv{r, d};
  const auto result = mosb::evaluate_front(sv, rv, eps, options);
  if (!result.achieved.is_infinite())  // infinite: no ε covers (an empty S, an unmet zero)
    check(mosb::uncovered_reference(sv, rv, result.achieved).empty());
  for (std::size_t k = 0; k < eps.size(); ++k)
    if (eps[k].num != 0 && !options.strict_dominance)
      check(result.coverage.at(k).covered == !(eps[k] < result.achieved));
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 2) return 0;
  const std::size_t d = 1 + (data[0] & 3);
  const int type = (data[0] >> 2) & 3;  // 0 integer, 1 f64, 2 and 3 f32
  mosb::EvalOptions options;
  options.strict_dominance = (data[0] >> 4) & 1;
  const std::size_t split = data[1];
  const std::vector<mosb::Ratio> eps{{0, 1}, {1, 100}, {1, 10}, {1, 1000000000000000000ULL}};
  try {
    if (type == 0)
      fuzz_integer(data + 2, size - 2, d, split, eps, options);
    else
      fuzz_double(doubles(data + 2, size - 2, type != 1), d, split, eps, options);
  } catch (const mosb::Error&) {
  }
  return 0;
}
