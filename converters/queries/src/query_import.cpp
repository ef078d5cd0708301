#include "mosb/converters/query_import.hpp"

#include "mosb/converters/text_input.hpp"
#include "mosb/converters/text_scan.hpp"
#include "mosb/error.hpp"
#include "mosb/format.hpp"

namespace mosb::converters {

namespace {

using namespace text;  // the shared primitives of text_scan.hpp

// Fields and --match texts are shown up to 60 bytes, more than a token elsewhere.
std::string quoted_field(std::string_view field) {
  return quoted(field, 60);
}

// A field of a data line, or one of the separators ',' and ';' (which are items of their own).
struct Item {
  std::string_view text;
  std::uint64_t column;  // 1-based
  bool separator;
};

bool is_blank(char c) {
  return c == ' ' || c == '\t';
}

void split_items(std::string_view line, std::vector<Item>& items) {
  items.clear();
  std::size_t i = 0;
  while (i < line.size()) {
    if (is_blank(line[i])) {
      ++i;
    } else if (line[i] == ',' || line[i] == ';') {
      items.push_back({line.substr(i, 1), i + 1, true});
      ++i;
    } else {
      const std::size_t start = i;
      while (i < line.size() && !is_blank(line[i]) && line[i] != ',' && line[i] != ';') ++i;
      items.push_back({line.substr(start, i - start), start + 1, false});
    }
  }
}

bool is_comment(const std::vector<Item>& items) {
  const auto first = items.front().text;
  return first[0] == '#' || first == "c";
}

// Graph paths differ in their ends (the file name), so a long one keeps its last characters.
std::string quoted_path(std::string_view path) {
  const std::size_t limit = 80;
  if (path.size() <= limit) return quoted_field(path);
  return "'..." + quoted(path.substr(path.size() - limit), limit).substr(1);
}

enum class LineForm { pair, graph };  // `s t` (or `s, t`, `s; t`) and `graph s t`

const char* form_text(LineForm form) {
  return form == LineForm::pair ? "'start goal'" : "'graph start goal'";
}

class QueryParser {
 public:
  QueryParser(const std::string& file, const QueryFileOptions& options)
      : file_(file), options_(options) {}

  void parse_line(std::string_view line, std::uint64_t number, std::vector<Query>& out) {
    line_ = number;
    split_items(line, items_);
    if (items_.empty() || is_comment(items_)) return;
    const auto end_column = line.size() + 1;
    const Item *graph = nullptr, *start = nullptr, *goal = nullptr;
    auto expect_field = [&](std::size_t k) -> const Item& {
      if (k >= items_.size())
        fail(end_column, std::string("missing field: expected ") + expected());
      if (items_[k].separator) fail(items_[k].column, "unexpected " + quoted_field(items_[k].text));
      return items_[k];
    };
    auto expect_end = [&](std::size_t k) {
      if (k < items_.size())
        fail(items_[k].column,
             "extra field " + quoted_field(items_[k].text) + ": expected " + expected());
    };
    start = &expect_field(0);
    if (items_.size() > 1 && items_[1].separator) {
      goal = &expect_field(2);
      expect_end(3);
    } else {
      goal = &expect_field(1);
      if (items_.size() > 2) {
        if (items_[2].separator)
          fail(items_[2].column, "unexpected " + quoted_field(items_[2].text));
        if (is_digits(start->text))
          fail(items_[2].column,
               "extra field " + quoted_field(items_[2].text) + ": expected " + expected());
        graph = start;
        start = goal;
        goal = &expect_field(2);
        expect_end(3);
      }
    }
    const LineForm form = graph ? LineForm::graph : LineForm::pair;
    if (!form_) {
      form_ = form;
      form_line_ = number;
    } else if (*form_ != form) {
      fail(1, std::string("a ") + form_text(form) + " line, but line " +
                  std::to_string(form_line_) + " is " + form_text(*form_));
    }
    if (form == LineForm::pair && options_.match)
      fail(1, {setting("match"),
               " " + quoted_field(*options_.match) + " given, but the lines have no graph field"});
    if (graph && !select(*graph)) return;
    out.push_back({parse_id(*start), parse_id(*goal)});
  }

  void finish(const std::vector<Query>& out) const {
    if (!out.empty()) return;
    if (options_.match && form_)
      throw Error(file_ + ": no line's graph field contains " + quoted_field(*options_.match));
    throw Error(file_ + ": no queries");
  }

 private:
  [[noreturn]] void fail(std::uint64_t column, const std::string& message) const {
    text::fail(file_, line_, column, message);
  }
  [[noreturn]] void fail(std::uint64_t column, Message message) const {
    text::fail(file_, line_, column, std::move(message));
  }

  const char* expected() const {
    if (form_ == LineForm::graph) return form_text(LineForm::graph);
    if (form_ == LineForm::pair) return form_text(LineForm::pair);
    return "'start goal' or 'graph start goal'";
  }

  // Whether a `graph s t` line is kept; at most one distinct graph may be kept.
  bool select(const Item& graph) {
    if (options_.match && graph.text.find(*options_.match) == std::string_view::npos) return false;
    if (graph_line_ == 0) {
      graph_ = graph.text;
      graph_line_ = line_;
    } else if (graph.text != graph_) {
      const std::string both = "(" + quoted_path(graph_) + " on line " +
                               std::to_string(graph_line_) + ", " + quoted_path(graph.text) +
                               " here)";
      if (options_.match)
        fail(graph.column, {setting("match"), " " + quoted_field(*options_.match) +
                                                  " selects more than one graph " + both});
      fail(graph.column, {"the file names more than one graph " + both + ": choose one with ",
                          setting("match"), " TEXT"});
    }
    return true;
  }

  std::uint32_t parse_id(const Item& item) const {
    const auto s = item.text;
    if (!is_digits(s)) fail(item.column, "expected a vertex id, found " + quoted_field(s));
    const auto value = text::to_u64(s);
    const std::uint64_t base = options_.id_base, n = options_.vertex_count;
    if (!value || *value < base || *value - base >= n)
      fail(item.column, "vertex id " + quoted_field(s) + " outside " +
                            (n == 0 ? std::string("(none: the graph has no vertices)")
                                    : std::to_string(base) + ".." + std::to_string(n - 1 + base)));
    return static_cast<std::uint32_t>(*value - base);
  }

  const std::string& file_;
  const QueryFileOptions& options_;
  std::vector<Item> items_;
  std::uint64_t line_ = 0;
  std::optional<LineForm> form_;
  std::uint64_t form_line_ = 0;
  std::string graph_;
  std::uint64_t graph_line_ = 0;
};

std::vector<Query> parse_queries(text::LineScanner& lines, const std::string& display_name,
                                 const QueryFileOptions& options) {
  if (options.id_base > 1) throw Error(display_name + ": id base must be 0 or 1");
  // Ids are u32 with one value to spare (spec/FORMAT.md §4).
  if (options.vertex_count > format::kMaxCount)
    throw Error(display_name + ": vertex count exceeds 2^32-2");
  QueryParser parser(display_name, options);
  std::vector<Query> out;
  std::string_view line;
  while (lines.next(line)) {
    // A UTF-8 byte-order mark; columns count from after it.
    if (lines.number() == 1 && line.starts_with("\xEF\xBB\xBF")) line.remove_prefix(3);
    parser.parse_line(line, lines.number(), out);
  }
  parser.finish(out);
  return out;
}

}  // namespace

std::vector<Query> parse_query_file(std::string_view text, const std::string& display_name,
                                    const QueryFileOptions& options) {
  text::LineScanner lines(text);
  return parse_queries(lines, display_name, options);
}

std::vector<Query> parse_query_file(text::TextSource& source, const std::string& display_name,
                                    const QueryFileOptions& options) {
  text::LineScanner lines(source);
  return naming_input_on_out_of_memory(display_name,
                                       [&] { return parse_queries(lines, display_name, options); });
}

}  // namespace mosb::converters
