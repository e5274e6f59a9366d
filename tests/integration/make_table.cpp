// Writes the table the consumer projects read: two axes and an output that is multilinear in
// them, so that its interpolated value at any point inside is known in closed form
// (consumer/expected.h).

#include <cstdio>
#include <exception>
#include <vector>

#include "tests/runtime/table_writer.h"

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: %s TABLE.h5\n", argv[0]);
    return 2;
  }
  try {
    wrc::test::TableContent content;
    content.axes = {{"y", {-2.0, -1.0, 0.0, 1.0, 2.0}, "mm"}, {"spin", {-0.01, 0.0, 0.01}, "-"}};
    content.outputs = {"fx"};
    content.function = [](int, const std::vector<double>& x) {
      return 1.0 + 2.0 * x[0] + 300.0 * x[1] + 50.0 * x[0] * x[1];
    };
    wrc::test::WriteTable(argv[1], content);
    return 0;
  } catch (const std::exception& error) {
    std::fprintf(stderr, "%s\n", error.what());
    return 1;
  }
}
