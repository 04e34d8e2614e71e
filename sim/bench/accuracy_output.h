// The outputs of `ffsim bench`: the table on stdout, the CSV, the Markdown summary
// and one SVG plot (time against error, Pareto front marked) per scene and size.
#pragma once
#include <iosfwd>
#include <string>
#include <vector>

#include "sim/bench/accuracy_run.h"
#include "sim/bench/svg_plot.h"

namespace ffsim::bench {

void print_table(const AccuracyResult& r, std::ostream& out);
// One header line and one line per row.
std::string accuracy_csv(const AccuracyResult& r);
// The plot of one (scene, size): x median ms per frame (log), y mean disagreement (%).
Plot accuracy_plot(const AccuracyResult& r, const std::string& scene, int size);
std::string plot_file_name(const std::string& stem, const std::string& scene, int size);
std::string accuracy_markdown(const AccuracyConfig& c, const AccuracyResult& r);
// The Markdown section comparing geforce256, rgba10 and rgba12 against `ideal` per
// (scene, size, variant, filter); empty when no row has all three profiles.
std::string precision_ladder(const AccuracyResult& r);

// Writes DIR/STEM.csv, DIR/STEM.md and the plots; false (and a message on err) on an I/O error.
bool write_accuracy_files(const AccuracyConfig& c, const AccuracyResult& r, std::ostream& err);

}  // namespace ffsim::bench
