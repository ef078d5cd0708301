// The fork server program's bytes, from mosb_fork_server_image to mosb_fork_server_image_end.
#pragma once

extern "C" {
extern const char mosb_fork_server_image[];
extern const char mosb_fork_server_image_end[];
}
