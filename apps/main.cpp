// zenith — planetary atmospheres for domes, projector clusters and display walls.
#include "apps/command_line.h"

int main(int argc, char** argv) { return zenith::app::run_command_line(argc, argv); }
