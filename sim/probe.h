// Single-pixel tracing (`ffsim replay --probe X,Y`): stages that touch the probed
// pixel record, in words, their input and output there (codes and real values).
// The trace executor prints the records of each pass and clears the log.
//
// A stage records like this (cheap when no probe is set):
//
//   if (probe_.hits(x, y)) probe_.record("clear", "color " + describe_color(fb_, x, y) + " ...");
#pragma once
#include <string>
#include <vector>

#include "sim/framebuffer.h"

namespace ffsim {

struct ProbeRecord {
  std::string stage;  // "clear", "write_fragments", "blend", "general_combiner 0", ...
  std::string text;
};

class ProbeLog {
 public:
  void set_target(int x, int y) {
    enabled_ = true;
    x_ = x;
    y_ = y;
  }
  void clear_target() { enabled_ = false; }
  bool enabled() const { return enabled_; }
  int x() const { return x_; }
  int y() const { return y_; }
  bool hits(int x, int y) const { return enabled_ && x == x_ && y == y_; }
  bool inside(const Rect& r) const {
    return enabled_ && x_ >= r.x && x_ < r.x + r.width && y_ >= r.y && y_ < r.y + r.height;
  }
  void record(std::string stage, std::string text) { records_.push_back({std::move(stage), std::move(text)}); }
  const std::vector<ProbeRecord>& records() const { return records_; }
  std::vector<ProbeRecord> take() {
    std::vector<ProbeRecord> r;
    r.swap(records_);
    return r;
  }

 private:
  bool enabled_ = false;
  int x_ = 0, y_ = 0;
  std::vector<ProbeRecord> records_;
};

// "codes (255, 128, 0, 255) = (1, 0.50196, 0, 1)" for fixed colour,
// "values (1, 0.5, 0, 1)" for float colour.
std::string describe_color(const Framebuffer& fb, int x, int y);
// Fragment colour as carried by a FragmentSpan element (codes or values, 4 channels).
std::string describe_codes(const std::uint16_t* codes, int bits);
std::string describe_values(const double* values);

}  // namespace ffsim
