// `ffsim diff A B`: compare two images or two dump directories.
#include <filesystem>
#include <map>
#include <ostream>
#include <set>

#include "sim/cli/cli.h"
#include "sim/cli/trace_cli.h"
#include "sim/image_diff.h"
#include "sim/image_io.h"

namespace ffsim::cli {

namespace fs = std::filesystem;

namespace {

bool is_image_file(const fs::path& p) {
  std::string e = p.extension().string();
  for (auto& c : e) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return e == ".png" || e == ".exr" || e == ".tif" || e == ".tiff";
}

// Image files under `dir`, relative paths, skipping hidden files (temporaries).
std::set<std::string> image_files(const fs::path& dir) {
  std::set<std::string> out;
  for (auto it = fs::recursive_directory_iterator(dir); it != fs::recursive_directory_iterator(); ++it) {
    const std::string fname = it->path().filename().string();
    if (!fname.empty() && fname[0] == '.') {
      if (it->is_directory()) it.disable_recursion_pending();
      continue;
    }
    if (it->is_regular_file() && is_image_file(it->path()))
      out.insert(fs::relative(it->path(), dir).generic_string());
  }
  return out;
}

}  // namespace

int run_diff(const std::vector<std::pair<std::string, std::pair<const Image*, const Image*>>>& pairs,
             const std::vector<std::string>& only_a, const std::vector<std::string>& only_b, const std::string& out_dir,
             bool json, std::ostream& out, std::ostream& err, const std::string& header_json) {
  int different = 0;
  std::vector<std::string> lines, objects, heatmaps;
  for (const auto& [name, ab] : pairs) {
    const ImageDiff d = diff_images(*ab.first, *ab.second);
    if (!d.identical()) ++different;
    lines.push_back(describe_diff(name, d));
    objects.push_back(json_diff(name, d));
    if (!d.identical() && d.same_shape && !out_dir.empty()) {
      try {
        fs::create_directories(out_dir);
        const std::string hm = (fs::path(out_dir) / heatmap_name(name)).string();
        const std::string tmp = (fs::path(out_dir) / trace::cat(".", heatmap_name(name))).string();
        write_image(tmp, d.heatmap);
        fs::rename(tmp, hm);
        heatmaps.push_back(hm);
      } catch (const std::exception& e) {
        err << "ffsim diff: " << e.what() << "\n";
        return 2;
      }
    }
  }
  for (const auto& n : only_a) lines.push_back(n + ": only in A");
  for (const auto& n : only_b) lines.push_back(n + ": only in B");
  different += static_cast<int>(only_a.size() + only_b.size());
  if (json) {
    out << "{" << header_json << "\"identical\": " << (different ? "false" : "true") << ", \"images\": [";
    for (std::size_t k = 0; k < objects.size(); ++k) out << (k ? ", " : "") << objects[k];
    out << "], \"only_in_a\": " << json_string_array(only_a) << ", \"only_in_b\": " << json_string_array(only_b)
        << ", \"heatmaps\": " << json_string_array(heatmaps) << "}\n";
  } else {
    for (const auto& l : lines) out << l << "\n";
    for (const auto& h : heatmaps) out << "wrote " << h << "\n";
    out << pairs.size() << " image" << (pairs.size() == 1 ? "" : "s") << " compared, " << different << " different\n";
  }
  return different ? 1 : 0;
}

Subcommand diff_command() {
  Subcommand s;
  s.name = "diff";
  s.summary = "compare two images or dump sets";
  s.usage =
      "usage: ffsim diff A B [--out DIR] [--json]\n\n"
      "Compares two images (PNG, TIFF, EXR) or two directories of dumps (files matched\n"
      "by relative path). Samples are compared as real values, so an 8-bit PNG and the\n"
      "EXR of the same buffer are equal. Per image: the pixels that differ, the largest\n"
      "difference per channel in LSBs (8-bit unless both images are 16-bit), RMSE and\n"
      "PSNR, and for one-channel images (alpha, stencil, shadow masks) the lit/shadow\n"
      "disagreements (lit: value > 0). --out DIR writes a heat map diff-<name>.png for\n"
      "every image that differs.\n\n"
      "Exit code 0 identical, 1 different, 2 error (unreadable file, usage).\n";
  s.run = [](const std::vector<std::string>& args, std::ostream& out, std::ostream& err) {
    std::vector<std::string> paths;
    std::string out_dir;
    bool json = false;
    for (std::size_t i = 0; i < args.size(); ++i) {
      const std::string& a = args[i];
      if (a == "--out") {
        if (i + 1 >= args.size() || args[i + 1].empty()) return usage_error(err, "diff", "--out needs a directory");
        out_dir = args[++i];
      } else if (a == "--json") json = true;
      else if (!a.empty() && a[0] == '-') return usage_error(err, "diff", std::string("unknown argument `") + a + "`");
      else paths.push_back(a);
    }
    if (paths.size() != 2) return usage_error(err, "diff", "expected two images or two directories");
    std::error_code ec;
    const bool da = fs::is_directory(paths[0], ec), db = fs::is_directory(paths[1], ec);
    if (da != db) {
      err << "ffsim diff: cannot compare a directory with a file (" << paths[0] << ", " << paths[1] << ")\n";
      return 2;
    }
    try {
      std::map<std::string, std::pair<Image, Image>> images;
      std::vector<std::string> only_a, only_b;
      if (da) {
        const auto fa = image_files(paths[0]), fb = image_files(paths[1]);
        for (const auto& f : fa) {
          if (!fb.count(f)) { only_a.push_back(f); continue; }
          images[f] = {read_image((fs::path(paths[0]) / f).string()), read_image((fs::path(paths[1]) / f).string())};
        }
        for (const auto& f : fb)
          if (!fa.count(f)) only_b.push_back(f);
      } else {
        images[fs::path(paths[0]).filename().string()] = {read_image(paths[0]), read_image(paths[1])};
      }
      std::vector<std::pair<std::string, std::pair<const Image*, const Image*>>> pairs;
      for (const auto& [n, ab] : images) pairs.push_back({n, {&ab.first, &ab.second}});
      const std::string header = std::string("\"a\": ") + json_string(paths[0]) + ", \"b\": " + json_string(paths[1]) + ", ";
      return run_diff(pairs, only_a, only_b, out_dir, json, out, err, header);
    } catch (const std::exception& e) {
      err << "ffsim diff: " << e.what() << "\n";
      return 2;
    }
  };
  return s;
}

}  // namespace ffsim::cli
