// Checks of an EXR file's header made before OpenEXR reads it. OpenEXR 3.1 allocates whatever a
// header declares (a string attribute's length, line buffers sized by the data window and the
// channels), so a file of a few hundred bytes can make it allocate gigabytes.
#pragma once

#include <string>

namespace pm {

// Walks the header(s) without OpenEXR and throws InputError "EXR file '<path>': ..." when an
// attribute declares more bytes than the file holds, the header is cut short, the data window is
// not within 1x1 to 16384x16384 (the largest --resolution), or the buffers OpenEXR would decode
// into (a chunk of scanlines, or a tile) exceed 256 MiB. read_exr and exr_is_complete call it.
void check_exr_header(const std::string& path);

}  // namespace pm
