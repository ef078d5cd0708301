// The fork server program's bytes (fork_server.cpp), built first and carried in lib/run's
// read-only data: ForkServer starts it from memory. MOSB_FORK_SERVER is the built program's path.
#include "fork_server_image.hpp"

// NOLINTNEXTLINE(hicpp-no-assembler): .incbin is the one way to carry a built file's bytes.
asm(".pushsection .rodata\n"
    ".balign 16\n"
    ".globl mosb_fork_server_image\n"
    ".hidden mosb_fork_server_image\n"
    "mosb_fork_server_image:\n"
    ".incbin \"" MOSB_FORK_SERVER
    "\"\n"
    ".globl mosb_fork_server_image_end\n"
    ".hidden mosb_fork_server_image_end\n"
    "mosb_fork_server_image_end:\n"
    ".popsection\n");
