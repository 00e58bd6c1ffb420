#include "cli.hpp"

int main(int argc, char** argv) { return iblab::app::runCommandLine(argc, argv); }
