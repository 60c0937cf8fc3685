#pragma once
// The executables of the `freeplay` program hand commands to each other (cli/CMakeLists.txt): `freeplay` →
// `freeplay-run` for `run`/`suite` → `freeplay-full` for everything else and for runs that record or render.

namespace freeplay::cli {

/// Replaces this process with the executable `name` beside this one, with the same arguments (execv: same process
/// id, signals and standard streams); returns only when that fails, after saying why on stderr, with exit status 1.
int exec_sibling_program(const char* name, char** argv);

/// The arguments `run_program` was started with (for handing the command on to another executable).
char** program_arguments();

}  // namespace freeplay::cli
