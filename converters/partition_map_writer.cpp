#include "converters/partition_map_writer.hpp"

#include <cairo/cairo.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/error.hpp"

namespace lpsim {

namespace {

// Distinct colours for any number of parts: hues a golden angle apart, alternating in lightness.
void part_colour(int32_t p, double rgb[3]) {
  const double h = std::fmod(static_cast<double>(p) * 0.618033988749895, 1.0) * 6.0;
  const double s = 0.75, v = p % 2 == 0 ? 0.9 : 0.65;
  const int i = static_cast<int>(h);
  const double f = h - i, a = v * (1 - s), b = v * (1 - s * f), c = v * (1 - s * (1 - f));
  const double table[6][3] = {{v, c, a}, {b, v, a}, {a, v, c}, {a, b, v}, {c, a, v}, {v, a, b}};
  for (int k = 0; k < 3; ++k) rgb[k] = table[i % 6][k];
}

}  // namespace

void write_partition_map(const std::string& path, const Network& net, const std::vector<int32_t>& lane_part,
                         int32_t parts, int width) {
  double x0 = std::numeric_limits<double>::max(), y0 = x0, x1 = -x0, y1 = -x0;
  for (size_t i = 0; i < net.shape_x.size(); ++i) {
    x0 = std::min<double>(x0, net.shape_x[i]), x1 = std::max<double>(x1, net.shape_x[i]);
    y0 = std::min<double>(y0, net.shape_y[i]), y1 = std::max<double>(y1, net.shape_y[i]);
  }
  if (x0 > x1) x0 = y0 = 0, x1 = y1 = 1;
  const double margin = 10, span_x = std::max(x1 - x0, 1.0), span_y = std::max(y1 - y0, 1.0);
  const double scale = (width - 2 * margin) / span_x;
  const int height = std::max(1, static_cast<int>(std::ceil(span_y * scale + 2 * margin)));
  cairo_surface_t* surface = cairo_image_surface_create(CAIRO_FORMAT_RGB24, width, std::min(height, 20000));
  cairo_t* cr = cairo_create(surface);
  cairo_set_source_rgb(cr, 1, 1, 1);
  cairo_paint(cr);
  cairo_set_line_width(cr, std::clamp(scale * 3.0, 0.6, 4.0));
  cairo_set_line_cap(cr, CAIRO_LINE_CAP_ROUND);
  for (uint32_t l = 0; l < net.num_lanes(); ++l) {
    const uint32_t b = net.lane_shape_begin[l], e = net.lane_shape_begin[l + 1];
    if (e - b < 2) continue;
    double rgb[3] = {0.6, 0.6, 0.6};
    if (lane_part[l] >= 0 && lane_part[l] < parts) part_colour(lane_part[l], rgb);
    cairo_set_source_rgb(cr, rgb[0], rgb[1], rgb[2]);
    for (uint32_t i = b; i < e; ++i) {
      const double px = margin + (net.shape_x[i] - x0) * scale, py = margin + (y1 - net.shape_y[i]) * scale;
      if (i == b)
        cairo_move_to(cr, px, py);
      else
        cairo_line_to(cr, px, py);
    }
    cairo_stroke(cr);
  }
  cairo_destroy(cr);
  const cairo_status_t status = cairo_surface_write_to_png(surface, path.c_str());
  cairo_surface_destroy(surface);
  if (status != CAIRO_STATUS_SUCCESS)
    throw InputError(SourceLoc{path, 0},
                     std::string("cannot write the map: ") + cairo_status_to_string(status));
}

}  // namespace lpsim
