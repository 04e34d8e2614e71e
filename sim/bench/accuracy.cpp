#include "sim/bench/accuracy.h"

#include <ostream>

#include "sim/bench/accuracy_config.h"
#include "sim/bench/accuracy_output.h"
#include "sim/bench/accuracy_run.h"

namespace ffsim::bench {

std::string accuracy_usage() {
  return "usage: ffsim bench [--quick] [--sizes 256,512,1024] [--lights N|all] [--profiles geforce256,rgba10,...]\n"
         "                   [--variants NAME,...] [--filters nearest,linear] [--scenes polygon,terrain] [--repeat N]\n"
         "                   [--threads N] [--res N] [--rays N] [--out DIR] [--name STEM] [--traces DIR] [--no-write]\n"
         "  Run time against error (issue 9): every variant x profile x filter x scene x frame size over a sweep of\n"
         "  lights, against the exact ray cast and against the same trace under `ideal`. Table on stdout; STEM.csv,\n"
         "  STEM.md and STEM-<scene>-<size>.svg under DIR (default docs/results, STEM accuracy or accuracy-quick).\n"
         "  --quick: 256x256, 3 lights, geforce256 and ideal, LINEAR. Default: 256/512/1024, 48 lights, 5 profiles (long).\n"
         "  Exit 0, or 1 when a run failed (numbers never fail), 2 on a bad option. See docs/bench.md.\n";
}

int run_accuracy(const std::vector<std::string>& args, std::ostream& out, std::ostream& err) {
  std::string error;
  const auto config = parse_accuracy_args(args, error);
  if (!config) {
    err << "ffsim bench: " << error << " (ffsim bench --help)\n";
    return 2;
  }
  const AccuracyResult r = run_accuracy_config(*config, err);
  print_table(r, out);
  out << "\n" << r.rows.size() << " rows in " << static_cast<long long>(r.seconds + 0.5) << " s\n";
  bool ok = r.all_ok;
  if (config->write_files) {
    if (!write_accuracy_files(*config, r, err)) ok = false;
    else out << "wrote " << config->out_dir << "/" << config->name << ".csv, .md and the plots\n";
  }
  for (const auto& row : r.rows)
    if (!row.acc.ok) err << "ffsim bench: " << row.scene << " " << row.size << " " << row.variant.name << " " << row.profile << " "
                         << row.filter_text() << ": " << row.acc.error << "\n";
  return ok ? 0 : 1;
}

}  // namespace ffsim::bench
