// The measuring loop of `ffsim bench`: for every scene, frame size and light of
// the sweep, the exact reference once, then every variant under every profile and
// filter; errors per light, run time at the first light (warm-up + repeats).
#pragma once
#include <iosfwd>
#include <string>
#include <vector>

#include "sim/bench/accuracy_config.h"
#include "sim/bench/accuracy_metrics.h"

namespace ffsim::bench {

struct AccuracyRow {
  std::string scene;
  int size = 0;
  VariantSpec variant;
  std::string profile;  // "float64" for the CPU rows
  int filter = -1;      // 0 NEAREST, 1 LINEAR, -1 for the CPU rows
  RowAccumulator acc;
  bool pareto = false;  // on the time/disagreement front of its (scene, size)

  std::string filter_text() const { return filter < 0 ? "-" : filter_name(filter); }
  double mean_disagreement() const;  // NaN without lights
  Spread time_ms() const;
};

struct AccuracyResult {
  std::vector<AccuracyRow> rows;
  bool all_ok = true;
  double seconds = 0;  // wall time of the whole run
};

// Runs the configuration; progress lines go to `progress`. Never throws for a
// failed run (the row records it and all_ok turns false).
AccuracyResult run_accuracy_config(const AccuracyConfig& c, std::ostream& progress);

// Marks AccuracyRow::pareto: per (scene, size), the rows that ran, by (median time,
// mean disagreement).
void mark_pareto(std::vector<AccuracyRow>& rows);

}  // namespace ffsim::bench
