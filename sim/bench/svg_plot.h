// A small dependency-free SVG scatter plot: series of labelled points on linear or
// logarithmic axes, a title, and optional polylines (a Pareto front). Used by
// `ffsim bench` (time against error) and reusable by the other benchmarks.
//
//   Plot p;
//   p.title = "time vs error"; p.x_label = "ms per frame"; p.x_log = true;
//   p.series.push_back({"geforce256", {{1.5, 0.02, "imaging-hard"}}});
//   p.lines.push_back({"Pareto front", {{1.5, 0.02}, {9, 0.0}}});
//   write_svg("plot.svg", p);
#pragma once
#include <string>
#include <utility>
#include <vector>

namespace ffsim::bench {

struct PlotPoint {
  double x = 0, y = 0;
  std::string label;  // tooltip; also drawn next to the point when show_label and Plot::label_points
  bool show_label = true;
};

struct PlotSeries {
  std::string name;  // legend entry
  std::vector<PlotPoint> points;
  std::string color;  // CSS colour; empty: the next of a fixed palette
};

struct PlotLine {
  std::string name;  // legend entry
  std::vector<std::pair<double, double>> points;  // joined in the given order
  std::string color = "#d62728";
};

struct Plot {
  std::string title, x_label, y_label;
  bool x_log = false, y_log = false;  // log axes drop points <= 0 (counted in a note)
  int width = 960, height = 640;
  bool label_points = true;
  std::vector<PlotSeries> series;
  std::vector<PlotLine> lines;
};

// The SVG document (UTF-8 text). Never throws for data: non-finite points are
// skipped, an empty plot still gives well-formed axes.
std::string render_svg(const Plot& plot);
// Writes render_svg(plot) to path; false when the file cannot be written.
bool write_svg(const std::string& path, const Plot& plot);

// XML escaping of text content and attribute values (& < > " ').
std::string xml_escape(const std::string& s);

}  // namespace ffsim::bench
