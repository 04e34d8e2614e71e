#include "sim/bench/svg_plot.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <sstream>

namespace ffsim::bench {

std::string xml_escape(const std::string& s) {
  std::string o;
  for (char c : s) {
    switch (c) {
      case '&': o += "&amp;"; break;
      case '<': o += "&lt;"; break;
      case '>': o += "&gt;"; break;
      case '"': o += "&quot;"; break;
      case '\'': o += "&apos;"; break;
      default:
        // Control characters are not allowed in XML 1.0 text.
        if (static_cast<unsigned char>(c) >= 0x20 || c == '\t' || c == '\n') o += c;
    }
  }
  return o;
}

namespace {

std::string num(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.2f", v);
  return b;
}

std::string tick_text(double v) {
  char b[32];
  const double a = std::fabs(v);
  if (v == 0) return "0";
  if (a >= 1e5 || a < 1e-3) std::snprintf(b, sizeof b, "%.0e", v);
  else std::snprintf(b, sizeof b, "%g", v);
  return b;
}

// One axis: maps data to [0, 1] and gives its tick values.
struct Axis {
  bool log = false;
  double lo = 0, hi = 1;  // in data units (log: positive)

  void fit(std::vector<double> v) {
    v.erase(std::remove_if(v.begin(), v.end(), [&](double x) { return !std::isfinite(x) || (log && x <= 0); }), v.end());
    if (v.empty()) {
      lo = log ? 1 : 0;
      hi = log ? 10 : 1;
      return;
    }
    lo = *std::min_element(v.begin(), v.end());
    hi = *std::max_element(v.begin(), v.end());
    if (log) {
      lo = std::pow(10, std::floor(std::log10(lo)));
      hi = std::pow(10, std::ceil(std::log10(hi)));
      if (hi <= lo) hi = lo * 10;
    } else {
      if (lo > 0 && lo < 0.5 * hi) lo = 0;  // start at 0 when the data are not far from it
      if (hi <= lo) hi = lo + (lo == 0 ? 1 : std::fabs(lo) * 0.1);
      const double pad = 0.05 * (hi - lo);
      if (lo != 0) lo -= pad;
      hi += pad;
    }
  }
  double t(double v) const {
    if (log) return (std::log10(v) - std::log10(lo)) / (std::log10(hi) - std::log10(lo));
    return (v - lo) / (hi - lo);
  }
  std::vector<double> ticks() const {
    std::vector<double> out;
    if (log) {
      const int a = static_cast<int>(std::floor(std::log10(lo) + 1e-9)), b = static_cast<int>(std::ceil(std::log10(hi) - 1e-9));
      const bool minor = b - a <= 3;
      for (int e = a; e <= b; ++e)
        for (double m : {1.0, 2.0, 5.0}) {
          if (m != 1.0 && !minor) continue;
          const double v = m * std::pow(10, e);
          if (v >= lo * (1 - 1e-9) && v <= hi * (1 + 1e-9)) out.push_back(v);
        }
      return out;
    }
    const double span = hi - lo, raw = span / 6, p = std::pow(10, std::floor(std::log10(raw)));
    double step = p;
    for (double m : {1.0, 2.0, 5.0, 10.0})
      if (m * p >= raw) {
        step = m * p;
        break;
      }
    for (double v = std::ceil(lo / step) * step; v <= hi + 1e-9 * span; v += step) out.push_back(std::fabs(v) < 1e-12 * step ? 0 : v);
    return out;
  }
};

const char* kPalette[] = {"#1f77b4", "#ff7f0e", "#2ca02c", "#9467bd", "#8c564b", "#e377c2", "#7f7f7f", "#bcbd22", "#17becf", "#000000"};

}  // namespace

std::string render_svg(const Plot& p) {
  const double W = std::max(200, p.width), H = std::max(150, p.height);
  const double ml = 80, mr = 220, mt = 50, mb = 60;  // margins; the legend sits on the right
  const double pw = W - ml - mr, ph = H - mt - mb;
  Axis ax, ay;
  ax.log = p.x_log;
  ay.log = p.y_log;
  std::vector<double> xs, ys;
  for (const auto& s : p.series)
    for (const auto& q : s.points) xs.push_back(q.x), ys.push_back(q.y);
  for (const auto& l : p.lines)
    for (const auto& q : l.points) xs.push_back(q.first), ys.push_back(q.second);
  ax.fit(xs);
  ay.fit(ys);
  auto ok = [&](double x, double y) {
    return std::isfinite(x) && std::isfinite(y) && (!ax.log || x > 0) && (!ay.log || y > 0);
  };
  auto px = [&](double x) { return ml + pw * ax.t(x); };
  auto py = [&](double y) { return mt + ph * (1 - ay.t(y)); };

  std::ostringstream o;
  o << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
    << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << W << "\" height=\"" << H << "\" viewBox=\"0 0 " << W << " " << H
    << "\" font-family=\"sans-serif\" font-size=\"11\">\n"
    << "<rect x=\"0\" y=\"0\" width=\"" << W << "\" height=\"" << H << "\" fill=\"white\"/>\n"
    << "<text x=\"" << num(W / 2) << "\" y=\"24\" text-anchor=\"middle\" font-size=\"15\">" << xml_escape(p.title) << "</text>\n";
  // Grid and ticks.
  for (double v : ax.ticks()) {
    const double x = px(v);
    o << "<line x1=\"" << num(x) << "\" y1=\"" << num(mt) << "\" x2=\"" << num(x) << "\" y2=\"" << num(mt + ph)
      << "\" stroke=\"#e0e0e0\"/>\n<text x=\"" << num(x) << "\" y=\"" << num(mt + ph + 16) << "\" text-anchor=\"middle\">"
      << xml_escape(tick_text(v)) << "</text>\n";
  }
  for (double v : ay.ticks()) {
    const double y = py(v);
    o << "<line x1=\"" << num(ml) << "\" y1=\"" << num(y) << "\" x2=\"" << num(ml + pw) << "\" y2=\"" << num(y)
      << "\" stroke=\"#e0e0e0\"/>\n<text x=\"" << num(ml - 6) << "\" y=\"" << num(y + 4) << "\" text-anchor=\"end\">"
      << xml_escape(tick_text(v)) << "</text>\n";
  }
  o << "<rect x=\"" << num(ml) << "\" y=\"" << num(mt) << "\" width=\"" << num(pw) << "\" height=\"" << num(ph)
    << "\" fill=\"none\" stroke=\"black\"/>\n"
    << "<text x=\"" << num(ml + pw / 2) << "\" y=\"" << num(H - 18) << "\" text-anchor=\"middle\">" << xml_escape(p.x_label)
    << (ax.log ? " (log scale)" : "") << "</text>\n"
    << "<text transform=\"translate(18 " << num(mt + ph / 2) << ") rotate(-90)\" text-anchor=\"middle\">" << xml_escape(p.y_label)
    << (ay.log ? " (log scale)" : "") << "</text>\n";

  double ly = mt + 8;
  int dropped = 0;
  for (const auto& l : p.lines) {
    std::string pts;
    for (const auto& q : l.points)
      if (ok(q.first, q.second)) pts += num(px(q.first)) + "," + num(py(q.second)) + " ";
    if (!pts.empty()) o << "<polyline points=\"" << pts << "\" fill=\"none\" stroke=\"" << xml_escape(l.color) << "\" stroke-width=\"2\" stroke-dasharray=\"6 3\"/>\n";
    o << "<line x1=\"" << num(ml + pw + 14) << "\" y1=\"" << num(ly) << "\" x2=\"" << num(ml + pw + 34) << "\" y2=\"" << num(ly)
      << "\" stroke=\"" << xml_escape(l.color) << "\" stroke-width=\"2\" stroke-dasharray=\"6 3\"/>\n<text x=\"" << num(ml + pw + 40)
      << "\" y=\"" << num(ly + 4) << "\">" << xml_escape(l.name) << "</text>\n";
    ly += 16;
  }
  std::size_t k = 0;
  for (const auto& s : p.series) {
    const std::string c = s.color.empty() ? kPalette[k++ % (sizeof kPalette / sizeof *kPalette)] : s.color;
    o << "<g fill=\"" << xml_escape(c) << "\">\n";
    for (const auto& q : s.points) {
      if (!ok(q.x, q.y)) {
        ++dropped;
        continue;
      }
      o << "<circle cx=\"" << num(px(q.x)) << "\" cy=\"" << num(py(q.y)) << "\" r=\"3.5\"><title>" << xml_escape(q.label)
        << "</title></circle>\n";
      if (p.label_points && q.show_label && !q.label.empty())
        o << "<text x=\"" << num(px(q.x) + 5) << "\" y=\"" << num(py(q.y) - 4) << "\" font-size=\"8\" fill=\"#333\">" << xml_escape(q.label)
          << "</text>\n";
    }
    o << "</g>\n<circle cx=\"" << num(ml + pw + 24) << "\" cy=\"" << num(ly) << "\" r=\"4\" fill=\"" << xml_escape(c)
      << "\"/>\n<text x=\"" << num(ml + pw + 40) << "\" y=\"" << num(ly + 4) << "\">" << xml_escape(s.name) << "</text>\n";
    ly += 16;
  }
  if (dropped)
    o << "<text x=\"" << num(ml + pw + 14) << "\" y=\"" << num(ly + 8) << "\" font-size=\"9\">" << dropped
      << " point(s) not shown (not positive on a log axis)</text>\n";
  o << "</svg>\n";
  return o.str();
}

bool write_svg(const std::string& path, const Plot& plot) {
  std::ofstream f(path, std::ios::binary);
  f << render_svg(plot);
  return static_cast<bool>(f);
}

}  // namespace ffsim::bench
