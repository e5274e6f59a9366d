// toml++'s parser, compiled into the core once. Every other translation unit sees the
// declarations only (TOML_HEADER_ONLY=0, core/CMakeLists.txt). Debian ships toml++ as a shared
// library too, but linking it would keep the front end from being a static executable, and
// loading and relocating shared libraries is a large part of a small solve's start-up
// (tools/CMakeLists.txt).
#define TOML_IMPLEMENTATION 1
#include <toml++/toml.h>
