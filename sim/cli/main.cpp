// ffsim: thin entry point; everything lives in sim/cli (tested directly).
#include <exception>
#include <iostream>

#include "sim/cli/cli.h"

int main(int argc, char** argv) {
  try {
    return ffsim::cli::run(std::vector<std::string>(argv + 1, argv + argc), std::cout, std::cerr);
  } catch (const std::exception& e) {
    std::cerr << "ffsim: internal error: " << e.what() << "\n";
    return 1;
  }
}
