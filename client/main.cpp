// netmc: the client CLI. `netmc sim` runs studies in-process; with no arguments it runs the
// paper-001 study and prints the comparison table.

#include "client/cli_app.hpp"

int main(int argc, char** argv) { return netmc::cli::run_netmc(argc, argv); }
