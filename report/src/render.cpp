#include "mosb/report/render.hpp"

#include <cairo-pdf.h>
#include <cairo.h>
#include <librsvg/rsvg.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <memory>

#include "mosb/error.hpp"

namespace mosb::plots {

namespace {

constexpr double kPointsPerPixel = 72.0 / 96.0;

cairo_status_t append(void* closure, const unsigned char* data, unsigned int length) {
  static_cast<std::string*>(closure)->append(reinterpret_cast<const char*>(data), length);
  return CAIRO_STATUS_SUCCESS;
}

struct SurfaceDeleter {
  void operator()(cairo_surface_t* s) const { cairo_surface_destroy(s); }
};
struct ContextDeleter {
  void operator()(cairo_t* c) const { cairo_destroy(c); }
};
struct HandleDeleter {
  void operator()(RsvgHandle* h) const { g_object_unref(h); }
};

void check(cairo_status_t status, const char* what) {
  if (status != CAIRO_STATUS_SUCCESS)
    throw Error(std::string("cairo: ") + what + ": " + cairo_status_to_string(status));
}

}  // namespace

std::optional<ImageFormat> image_format_of(const std::filesystem::path& file) {
  std::string ext = file.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (ext.empty()) return std::nullopt;
  return kImageFormatNames.parse(std::string_view(ext).substr(1));
}

double parse_length(std::string_view text) {
  const auto fail = [&]() -> double {
    throw Error(ErrorCode::invalid_argument,
                "'" + std::string(text) +
                    "' is not a length: a number and a unit, in, pt, cm, mm or px (3.5in, 252pt)");
  };
  double value = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (ec != std::errc() || end == text.data()) return fail();
  const std::string_view unit(end, static_cast<std::size_t>(text.data() + text.size() - end));
  double points = 0;
  if (unit == "in")
    points = value * 72;
  else if (unit == "pt")
    points = value;
  else if (unit == "cm")
    points = value * 72 / 2.54;
  else if (unit == "mm")
    points = value * 72 / 25.4;
  else if (unit == "px")
    points = value * kPointsPerPixel;
  else
    return fail();
  if (!(points > 0) || points > 200 * 72)
    throw Error(ErrorCode::invalid_argument,
                "'" + std::string(text) + "': a figure's side must be above 0 and at most 200in");
  return points;
}

PageSize page_size(double svg_width_px, double svg_height_px, const RenderSize& size) {
  PageSize p;
  const double w = svg_width_px * kPointsPerPixel, h = svg_height_px * kPointsPerPixel;
  if (size.width_pt && size.height_pt) {
    p.width_pt = *size.width_pt, p.height_pt = *size.height_pt;
  } else if (size.width_pt) {
    p.width_pt = *size.width_pt, p.height_pt = *size.width_pt * h / w;
  } else if (size.height_pt) {
    p.height_pt = *size.height_pt, p.width_pt = *size.height_pt * w / h;
  } else {
    p.width_pt = w, p.height_pt = h;
  }
  p.width_px = std::max(1, static_cast<int>(std::lround(p.width_pt / 72 * size.dpi)));
  p.height_px = std::max(1, static_cast<int>(std::lround(p.height_pt / 72 * size.dpi)));
  return p;
}

std::string render_svg(const std::string& svg, ImageFormat format, const RenderSize& size) {
  if (format == ImageFormat::svg) return svg;
  GError* error = nullptr;
  std::unique_ptr<RsvgHandle, HandleDeleter> handle(
      rsvg_handle_new_from_data(reinterpret_cast<const guint8*>(svg.data()), svg.size(), &error));
  if (!handle) {
    const std::string message = error ? error->message : "unknown error";
    if (error) g_error_free(error);
    throw Error("librsvg cannot read the figure: " + message);
  }
  double width_px = 0, height_px = 0;
  if (!rsvg_handle_get_intrinsic_size_in_pixels(handle.get(), &width_px, &height_px) ||
      !(width_px > 0) || !(height_px > 0))
    throw Error("librsvg: the figure has no size in pixels");
  const auto page = page_size(width_px, height_px, size);
  std::string out;
  std::unique_ptr<cairo_surface_t, SurfaceDeleter> surface;
  double scale = 1;  // user units (points or pixels) per point
  if (format == ImageFormat::pdf) {
    surface.reset(cairo_pdf_surface_create_for_stream(append, &out, page.width_pt, page.height_pt));
    check(cairo_surface_status(surface.get()), "PDF surface");
    // No creation date: the same figure, the same bytes.
    cairo_pdf_surface_set_metadata(surface.get(), CAIRO_PDF_METADATA_CREATE_DATE, "");
    cairo_pdf_surface_set_metadata(surface.get(), CAIRO_PDF_METADATA_CREATOR, "mosb");
  } else {
    surface.reset(cairo_image_surface_create(CAIRO_FORMAT_ARGB32, page.width_px, page.height_px));
    check(cairo_surface_status(surface.get()), "image surface");
    scale = size.dpi / 72;
  }
  {
    std::unique_ptr<cairo_t, ContextDeleter> cr(cairo_create(surface.get()));
    cairo_scale(cr.get(), scale, scale);
    cairo_set_source_rgb(cr.get(), 1, 1, 1);  // white, as the SVG's own background
    cairo_paint(cr.get());
    const RsvgRectangle viewport{0, 0, page.width_pt, page.height_pt};
    if (!rsvg_handle_render_document(handle.get(), cr.get(), &viewport, &error)) {
      const std::string message = error ? error->message : "unknown error";
      if (error) g_error_free(error);
      throw Error("librsvg cannot draw the figure: " + message);
    }
    check(cairo_status(cr.get()), "drawing");
  }
  if (format == ImageFormat::png)
    check(cairo_surface_write_to_png_stream(surface.get(), append, &out), "PNG");
  cairo_surface_finish(surface.get());
  check(cairo_surface_status(surface.get()), "finishing");
  return out;
}

}  // namespace mosb::plots
