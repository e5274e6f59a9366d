// C++ side of the C test (see c_api_test_support.h). Also compiled into wrc_runtime_tests by
// the directory glob, where it is unused.

#include "tests/runtime/c_api_test_support.h"

#include <cstdio>
#include <cstring>
#include <exception>
#include <filesystem>
#include <string>
#include <vector>

#include <unistd.h>

#include "tests/runtime/table_writer.h"

extern "C" int wrc_test_write_c_table(char* path, size_t capacity) {
  try {
    const std::string name = (std::filesystem::temp_directory_path() /
                              ("wrc-c-test-" + std::to_string(::getpid()) + ".h5"))
                                 .string();
    if (name.size() + 1 > capacity) return -1;
    wrc::test::TableContent content;
    content.axes = {{"y", {-2.0, -1.0, 0.0, 1.0, 2.0}, "mm"}, {"spin", {-0.01, 0.0, 0.01}, "-"}};
    content.outputs = {"fx", "fy"};
    content.function = [](int k, const std::vector<double>& x) {
      return k == 0 ? 1.0 + 2.0 * x[0] + 300.0 * x[1] + 50.0 * x[0] * x[1] : x[0] * x[0];
    };
    wrc::test::WriteTable(name, content);
    std::memcpy(path, name.c_str(), name.size() + 1);
    return 0;
  } catch (const std::exception& error) {
    std::fprintf(stderr, "wrc_test_write_c_table: %s\n", error.what());
    return -1;
  }
}

extern "C" void wrc_test_remove(const char* path) {
  std::error_code ignored;
  std::filesystem::remove(path, ignored);
}
