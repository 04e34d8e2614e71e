// Pixel ownership and the scissor test (GL 1.2.1 §4.1.1, §4.1.2): a fragment at
// (xw, yw) survives iff it lies in the window and, when the scissor test is
// enabled, left <= xw < left + width and bottom <= yw < bottom + height.
// Both are rectangles, so on a span they cut one contiguous index range.
#pragma once

namespace ffsim {

struct ScissorBox {
  bool enabled = false;
  int x = 0, y = 0, width = 0, height = 0;
  bool operator==(const ScissorBox&) const = default;
};

// Fragments [begin, end) of a span survive (begin == end: none).
struct SpanRange {
  int begin = 0, end = 0;
  bool empty() const { return begin >= end; }
};

// The rectangle a fragment may be written to: the window [0,w)x[0,h),
// intersected with the scissor box when enabled. Width/height 0 when empty.
struct WriteRect {
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;  // half-open [x0,x1) x [y0,y1)
};
WriteRect write_rect(const ScissorBox& scissor, int window_width, int window_height);

// The surviving index range of the span (row y, fragments x0 .. x0+count-1).
SpanRange scissor_span(const WriteRect& r, int y, int x0, int count);

}  // namespace ffsim
