#include "program.hpp"

int main(int argc, char** argv) {
  return mosb::cli::main(argc, argv);
}
