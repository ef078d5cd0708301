#include "mosb/report/svg.hpp"

#include <cmath>
#include <cstdio>

namespace mosb::plots {

Svg::Svg(double width, double height) : width_(width), height_(height) {}

std::string Svg::number(double v) {
  if (!std::isfinite(v)) v = 0;
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.2f", v);
  std::string s = buffer;
  while (!s.empty() && s.back() == '0') s.pop_back();
  if (!s.empty() && s.back() == '.') s.pop_back();
  return s == "-0" ? "0" : s;
}

std::string Svg::escape(std::string_view text) {
  std::string out;
  for (char c : text) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      case '\'':
        out += "&apos;";
        break;
      default:
        // XML 1.0 allows no other C0 control, not even as a character reference: U+FFFD instead.
        if (static_cast<unsigned char>(c) < 0x20 && c != '\t' && c != '\n' && c != '\r')
          out += "\xEF\xBF\xBD";
        else
          out += c;
    }
  }
  return out;
}

void Svg::rect(double x, double y, double w, double h, std::string_view fill,
               std::string_view stroke, double stroke_width, double opacity) {
  body_ += "<rect x=\"" + number(x) + "\" y=\"" + number(y) + "\" width=\"" + number(w) +
           "\" height=\"" + number(h) + "\" fill=\"" + escape(fill) + "\" stroke=\"" +
           escape(stroke) + "\" stroke-width=\"" + number(stroke_width) + "\"";
  if (opacity < 1) body_ += " fill-opacity=\"" + number(opacity) + "\"";
  body_ += "/>\n";
}

void Svg::line(double x1, double y1, double x2, double y2, std::string_view stroke,
               double stroke_width) {
  body_ += "<line x1=\"" + number(x1) + "\" y1=\"" + number(y1) + "\" x2=\"" + number(x2) +
           "\" y2=\"" + number(y2) + "\" stroke=\"" + escape(stroke) + "\" stroke-width=\"" +
           number(stroke_width) + "\"/>\n";
}

void Svg::circle(double cx, double cy, double r, std::string_view fill, std::string_view stroke,
                 double stroke_width, double opacity) {
  body_ += "<circle cx=\"" + number(cx) + "\" cy=\"" + number(cy) + "\" r=\"" + number(r) +
           "\" fill=\"" + escape(fill) + "\" stroke=\"" + escape(stroke) + "\"";
  if (stroke != "none") body_ += " stroke-width=\"" + number(stroke_width) + "\"";
  if (opacity < 1) body_ += " fill-opacity=\"" + number(opacity) + "\"";
  body_ += "/>\n";
}

void Svg::text(double x, double y, std::string_view content, std::string_view anchor, double size,
               double rotate, std::string_view fill) {
  body_ += "<text x=\"" + number(x) + "\" y=\"" + number(y) + "\" text-anchor=\"" + escape(anchor) +
           "\" font-size=\"" + number(size) + "\" fill=\"" + escape(fill) + "\"";
  if (rotate != 0)
    body_ += " transform=\"rotate(" + number(rotate) + " " + number(x) + " " + number(y) + ")\"";
  body_ += ">" + escape(content) + "</text>\n";
}

void Svg::polyline(std::string_view points, std::string_view stroke, double stroke_width) {
  body_ += R"(<polyline points=")" + escape(points) + R"(" fill="none" stroke=")" + escape(stroke) +
           R"(" stroke-width=")" + number(stroke_width) + "\"/>\n";
}

void Svg::begin_group(std::string_view attributes) {
  body_ += "<g " + std::string(attributes) + ">\n";
}

void Svg::end_group() {
  body_ += "</g>\n";
}

std::string Svg::str() const {
  return std::string(R"(<?xml version="1.0" encoding="UTF-8"?>)") + "\n" + element();
}

std::string Svg::element() const {
  return std::string(R"(<svg xmlns="http://www.w3.org/2000/svg" width=")") + number(width_) +
         "\" height=\"" + number(height_) + "\" viewBox=\"0 0 " + number(width_) + " " +
         number(height_) + R"(" font-family="DejaVu Sans, Arial, sans-serif")" +
         (crisp_ ? std::string(R"( shape-rendering="crispEdges")") : std::string()) + ">\n" +
         R"(<rect width="100%" height="100%" fill="#fff"/>)" + "\n" + body_ + "</svg>\n";
}

}  // namespace mosb::plots
