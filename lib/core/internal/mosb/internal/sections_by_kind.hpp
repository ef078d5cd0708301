// A section table's sections grouped by kind, and the checks every reader of a file kind makes
// with them: the one walk over the table that GraphReader and SolutionReader check their kinds by
// and unpacking finds the CSR by.
#pragma once

#include <array>
#include <cstddef>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "mosb/container.hpp"

namespace mosb {

// The indices of each known kind's sections, in table order, found in one walk. A section of a
// kind this reader does not know (a later minor's) is in no group: every reader ignores it. The
// checks throw mosb::Error (ErrorCode::damaged) "DISPLAY_NAME: section 'NAME': problem", as the
// readers' own checks do.
class SectionsByKind {
 public:
  // `sections` and `display_name` must outlive this object.
  SectionsByKind(std::span<const Section> sections, std::string_view display_name);

  // The indices of the sections of `kind`, in table order.
  std::span<const std::size_t> all(format::SectionKind kind) const {
    return indices_[static_cast<std::size_t>(kind)];
  }
  // The index of the one section of `kind`, SIZE_MAX when there is none; refuses a second ("a
  // second KIND section", naming the second).
  std::size_t single(format::SectionKind kind) const;
  // The same for a kind held as `type` x 1: the first section's shape is checked before a second
  // one is refused.
  std::size_t single(format::SectionKind kind, format::ElementType type) const;
  // Refuses a section that is not `type` x 1 ("must be TYPE x 1").
  void expect_shape(const Section& s, format::ElementType type) const;
  // Refuses a cost column (an instance's cost, a solution file's front_cost) whose type is not
  // unsigned or float, or whose width is not 1.
  void expect_cost_column(const Section& s) const;

 private:
  [[noreturn]] void fail(const Section& s, const std::string& what) const;

  std::span<const Section> sections_;
  std::string_view display_name_;
  std::array<std::vector<std::size_t>, format::kLastSectionKind + 1> indices_;
};

}  // namespace mosb
