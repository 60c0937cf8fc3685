// `freeplay-full`: every subcommand of `freeplay` (the light `freeplay` executable runs this one for all but
// `--version` and `validate`, so that those start without loading the simulation's libraries).

#include "program.hpp"

int main(int argc, char** argv) { return freeplay::cli::run_program(argc, argv); }
