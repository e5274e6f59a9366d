// toml++'s implementation, compiled with the fuzzing instrumentation (see CMakeLists.txt).
#undef TOML_IMPLEMENTATION
#define TOML_IMPLEMENTATION 1
#include <toml++/toml.h>
