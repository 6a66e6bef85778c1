// zenith — planetary atmospheres for domes, projector clusters and display walls.
#include "apps/command_line.h"
#include "core/huge_page_heap.h"

int main(int argc, char** argv) {
  zenith::core::restart_with_huge_page_heap(argv);  // first: the heap's pages are chosen when a program starts
  return zenith::app::run_command_line(argc, argv);
}
