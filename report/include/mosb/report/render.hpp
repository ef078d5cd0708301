// Figures as PDF and PNG for a paper: an SVG document (plots.hpp) rendered by librsvg onto a cairo
// surface. A component of its own (mosb_report_render), so that only the program links librsvg and
// cairo; the reader and the SVG writers need neither.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

#include "mosb/enum_names.hpp"

namespace mosb::plots {

enum class ImageFormat { svg, pdf, png };
// Each format's name, also its file name extension: `--figure-format`'s choices and the files'.
inline constexpr auto kImageFormatNames = enum_names<ImageFormat>({
    {ImageFormat::svg, "svg"},
    {ImageFormat::pdf, "pdf"},
    {ImageFormat::png, "png"},
});

// By the file name's extension (.svg, .pdf, .png, any case: kImageFormatNames); nullopt for
// another.
std::optional<ImageFormat> image_format_of(const std::filesystem::path& file);

// A length in points (1/72 in): a number with a unit, "3.5in", "252pt", "8.9cm", "89mm" or
// "600px" (1 px = 1/96 in, the SVG's unit). Throws mosb::Error (ErrorCode::invalid_argument)
// saying what a length looks like for anything else, or for a length not above 0 or above 200 in.
double parse_length(std::string_view text);

// The printed size: width and height in points (either alone keeps the SVG's aspect ratio; both
// fit the figure inside, centred; neither: the SVG's own size, 1 px = 0.75 pt), and a PNG's
// resolution in dots per inch.
struct RenderSize {
  std::optional<double> width_pt, height_pt;
  double dpi = 150;
};

// The page size in points and, for PNG, the image size in pixels (rounded, at least 1).
struct PageSize {
  double width_pt = 0, height_pt = 0;
  int width_px = 0, height_px = 0;
};
PageSize page_size(double svg_width_px, double svg_height_px, const RenderSize& size);

// `svg` (a complete document) as a PDF (vector, one page, text as text; no creation date, so the
// same figure gives the same bytes) or a PNG (8-bit RGBA on white). Throws mosb::Error when librsvg
// cannot read the document or cairo fails. ImageFormat::svg returns `svg` unchanged.
std::string render_svg(const std::string& svg, ImageFormat format, const RenderSize& size);

}  // namespace mosb::plots
