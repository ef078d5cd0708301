// A minimal SVG 1.1 document writer: shapes and text with attributes escaped; numbers printed with
// fixed precision so the same figure gives the same bytes.
#pragma once

#include <string>
#include <string_view>

namespace mosb::plots {

class Svg {
 public:
  Svg(double width, double height);

  void rect(double x, double y, double w, double h, std::string_view fill,
            std::string_view stroke = "none", double stroke_width = 1, double opacity = 1);
  void line(double x1, double y1, double x2, double y2, std::string_view stroke,
            double stroke_width = 1);
  // stroke-width is written only with a stroke, fill-opacity only below 1.
  void circle(double cx, double cy, double r, std::string_view fill,
              std::string_view stroke = "none", double stroke_width = 1, double opacity = 1);
  // anchor: start, middle or end; rotate: degrees about (x, y).
  void text(double x, double y, std::string_view content, std::string_view anchor = "start",
            double size = 12, double rotate = 0, std::string_view fill = "#000");
  // An open path through the points "x,y x,y ...".
  void polyline(std::string_view points, std::string_view stroke, double stroke_width = 1.5);

  // <g ATTRIBUTES> ... </g>; the attributes are written as given (the caller escapes values).
  void begin_group(std::string_view attributes);
  void end_group();

  // Pixel-aligned shapes (maps: adjacent cells without anti-aliased seams).
  void set_crisp_edges() { crisp_ = true; }

  // The whole document, closed.
  std::string str() const;
  // The <svg> element alone, for inclusion in an HTML page.
  std::string element() const;

  static std::string number(double v);  // at most 2 decimals, no trailing zeros
  static std::string escape(std::string_view text);

 private:
  double width_, height_;
  std::string body_;
  bool crisp_ = false;
};

}  // namespace mosb::plots
