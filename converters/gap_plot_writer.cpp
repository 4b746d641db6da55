#include "converters/gap_plot_writer.hpp"

#include <cairo/cairo.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/error.hpp"

namespace lpsim {

void write_gap_plot(const std::string& path, const std::vector<double>& gaps) {
  constexpr int kWidth = 800, kHeight = 500;
  constexpr double kLeft = 80, kRight = 20, kTop = 30, kBottom = 50;
  // The decades the positive gaps span (at least one).
  double lo = 1, hi = 1;
  bool any = false;
  for (double g : gaps)
    if (g > 0) {
      lo = any ? std::min(lo, g) : g;
      hi = any ? std::max(hi, g) : g;
      any = true;
    }
  const int first_decade = static_cast<int>(std::floor(std::log10(lo)));
  const int last_decade = std::max(first_decade + 1, static_cast<int>(std::ceil(std::log10(hi))));
  const double plot_w = kWidth - kLeft - kRight, plot_h = kHeight - kTop - kBottom;
  const double last_iteration = std::max<double>(1, double(gaps.size()) - 1);
  auto x_of = [&](double i) { return kLeft + plot_w * i / last_iteration; };
  auto y_of = [&](double g) {
    return kTop + plot_h * (1 - (std::log10(g) - first_decade) / double(last_decade - first_decade));
  };

  cairo_surface_t* surface = cairo_image_surface_create(CAIRO_FORMAT_RGB24, kWidth, kHeight);
  cairo_t* cr = cairo_create(surface);
  cairo_set_source_rgb(cr, 1, 1, 1);
  cairo_paint(cr);
  cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
  cairo_set_font_size(cr, 13);
  char label[32];
  // Decade lines and labels.
  cairo_set_line_width(cr, 1);
  for (int d = first_decade; d <= last_decade; ++d) {
    const double y = y_of(std::pow(10.0, d));
    cairo_set_source_rgb(cr, 0.85, 0.85, 0.85);
    cairo_move_to(cr, kLeft, y);
    cairo_line_to(cr, kLeft + plot_w, y);
    cairo_stroke(cr);
    cairo_set_source_rgb(cr, 0, 0, 0);
    std::snprintf(label, sizeof label, "1e%d", d);
    cairo_move_to(cr, 20, y + 4);
    cairo_show_text(cr, label);
  }
  // Iteration ticks, about ten.
  const int step = std::max(1, static_cast<int>(std::ceil(last_iteration / 10)));
  for (int i = 0; i <= static_cast<int>(last_iteration); i += step) {
    std::snprintf(label, sizeof label, "%d", i);
    cairo_move_to(cr, x_of(i) - 4, kTop + plot_h + 20);
    cairo_show_text(cr, label);
  }
  cairo_move_to(cr, kLeft + plot_w / 2 - 30, kHeight - 10);
  cairo_show_text(cr, "iteration");
  cairo_move_to(cr, kLeft, 20);
  cairo_show_text(cr, "relative gap");
  // Axes, then the gaps.
  cairo_rectangle(cr, kLeft, kTop, plot_w, plot_h);
  cairo_stroke(cr);
  cairo_set_source_rgb(cr, 0.1, 0.3, 0.8);
  cairo_set_line_width(cr, 2);
  bool open = false;
  for (size_t i = 0; i < gaps.size(); ++i) {
    if (!(gaps[i] > 0)) {
      open = false;
      continue;
    }
    if (open)
      cairo_line_to(cr, x_of(double(i)), y_of(gaps[i]));
    else
      cairo_move_to(cr, x_of(double(i)), y_of(gaps[i]));
    open = true;
  }
  cairo_stroke(cr);
  for (size_t i = 0; i < gaps.size(); ++i)
    if (gaps[i] > 0) {
      cairo_arc(cr, x_of(double(i)), y_of(gaps[i]), 3, 0, 2 * M_PI);
      cairo_fill(cr);
    }
  cairo_destroy(cr);
  const cairo_status_t status = cairo_surface_write_to_png(surface, path.c_str());
  cairo_surface_destroy(surface);
  if (status != CAIRO_STATUS_SUCCESS)
    throw InputError(path + ": cannot write the plot: " + cairo_status_to_string(status));
}

}  // namespace lpsim
