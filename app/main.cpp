#include <CLI/CLI.hpp>

int main(int argc, char** argv) {
  CLI::App app{"iarap: as-rigid-as-possible surface deformation"};
  CLI11_PARSE(app, argc, argv);
  return 0;
}
