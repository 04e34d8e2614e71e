// `ffsim demo`: builds a context, fills the framebuffer with the documented test
// pattern (sim/test_pattern.h), writes it as PNG and EXR and prints the content
// hashes. It exercises profile, framebuffer, image I/O and hashing end to end.
#include <filesystem>
#include <ostream>

#include "sim/cli/cli.h"
#include "sim/context.h"
#include "sim/hash.h"
#include "sim/image_io.h"
#include "sim/profile_io.h"
#include "sim/test_pattern.h"

namespace ffsim::cli {

Subcommand demo_command() {
  Subcommand s;
  s.name = "demo";
  s.summary = "fill a framebuffer with the test pattern, write PNG/EXR, print hashes";
  s.usage =
      "usage: ffsim demo [--out DIR] [--profile NAME|FILE] [--size WxH]\n\n"
      "Fills a framebuffer with the documented test pattern (ramps, checker, XOR alpha,\n"
      "stencil and depth ramps), writes DIR/demo-color.png, demo-alpha.png,\n"
      "demo-stencil.png and demo-color.exr, and prints each buffer's content hash.\n"
      "Defaults: --out out/demo, --profile geforce256, --size 256x256.\n";
  s.run = [](const std::vector<std::string>& args, std::ostream& out, std::ostream& err) {
    std::string dir = "out/demo", profile = "geforce256";
    int w = 256, h = 256;
    for (std::size_t i = 0; i < args.size(); ++i) {
      const std::string& a = args[i];
      auto value = [&](std::string& dst) {
        if (i + 1 >= args.size()) return false;
        dst = args[++i];
        return true;
      };
      std::string v;
      if (a == "--out") { if (!value(dir)) return usage_error(err, "demo", "--out needs a directory"); }
      else if (a == "--profile") { if (!value(profile)) return usage_error(err, "demo", "--profile needs a name or file"); }
      else if (a == "--size") {
        if (!value(v) || std::sscanf(v.c_str(), "%dx%d", &w, &h) != 2)
          return usage_error(err, "demo", "--size expects WxH, e.g. 256x256");
      } else return usage_error(err, "demo", "unknown argument `" + a + "`");
    }
    try {
      Context ctx(load_profile(profile), w, h);
      fill_test_pattern(ctx.framebuffer());
      std::filesystem::create_directories(dir);
      const Framebuffer& fb = ctx.framebuffer();
      write_image(dir + "/demo-color.png", color_image(fb));
      write_image(dir + "/demo-alpha.png", alpha_image(fb));
      write_image(dir + "/demo-color.exr", color_image(fb));
      if (fb.has_stencil()) write_image(dir + "/demo-stencil.png", stencil_image(fb));
      out << "profile " << ctx.profile().name << ", " << w << "x" << h << ", wrote " << dir << "/demo-*\n";
      out << "color   " << hash_hex(buffer_hash(fb, BufferKind::Color)) << "\n";
      out << "alpha   " << hash_hex(buffer_hash(fb, BufferKind::Alpha)) << "\n";
      if (fb.has_stencil()) out << "stencil " << hash_hex(buffer_hash(fb, BufferKind::Stencil)) << "\n";
      if (fb.has_depth()) out << "depth   " << hash_hex(buffer_hash(fb, BufferKind::Depth)) << "\n";
      return 0;
    } catch (const std::exception& e) {
      err << "ffsim demo: " << e.what() << "\n";
      return 1;
    }
  };
  return s;
}

}  // namespace ffsim::cli
