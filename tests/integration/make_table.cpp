// Writes the table the consumer projects read: two axes and an output that is multilinear in
// them, so that its interpolated value at any point inside is known in closed form
// (consumer/expected.h). With --wheelset: the synthetic wheelset table of
// tests/runtime/wheelset_table.h instead (the Python tests read it).

#include <cstdio>
#include <exception>
#include <string>
#include <vector>

#include "tests/runtime/table_writer.h"
#include "tests/runtime/wheelset_table.h"

int main(int argc, char** argv) {
  const bool wheelset = argc == 3 && std::string(argv[1]) == "--wheelset";
  if (argc != 2 && !wheelset) {
    std::fprintf(stderr, "usage: %s [--wheelset] TABLE.h5\n", argv[0]);
    return 2;
  }
  try {
    if (wheelset) {
      wrc::test::WriteWheelsetTable(argv[2]);
      return 0;
    }
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
