#include "blas_kernels.h"
#include "cli.h"

#include <iostream>

int main(int argc, char** argv) {
  phedra::cli::prefer_blas_kernels_for_this_cpu(argv);
  std::vector<std::string> args(argv + 1, argv + argc);
  return phedra::cli::run(args, std::cout, std::cerr);
}
