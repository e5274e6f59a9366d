// wrc_table_node_values / wrc_table_node_status: the grid data as stored, node by node.

#include <gtest/gtest.h>

#include <vector>

#include "tests/runtime/table_writer.h"
#include "wrc/runtime.hpp"

namespace {

TEST(RuntimeNodeData, ValuesAndStatusPerNodeInRowMajorOrder) {
  wrc::test::ScratchFile scratch("node-data");
  wrc::test::TableContent content;
  content.axes = {{"y", {-1.0, 0.0, 1.0}}, {"yaw", {0.0, 0.5}}};
  content.outputs = {"fx", "fy"};
  content.function = [](int k, const std::vector<double>& x) {
    return 10.0 * x[0] + x[1] + 100.0 * k;
  };
  content.status = [](const std::vector<double>& x) -> std::int8_t {
    return x[0] == 1.0 && x[1] == 0.5 ? 2 : 0;
  };
  wrc::test::WriteTable(scratch.path(), content);
  const wrc::Table table(scratch.path());
  const double* values = wrc_table_node_values(table.get());
  const signed char* status = wrc_table_node_status(table.get());
  ASSERT_NE(values, nullptr);
  ASSERT_NE(status, nullptr);
  int node = 0;
  for (const double y : {-1.0, 0.0, 1.0}) {
    for (const double yaw : {0.0, 0.5}) {  // the last axis fastest
      EXPECT_EQ(values[node * 2 + 0], 10.0 * y + yaw) << node;
      EXPECT_EQ(values[node * 2 + 1], 10.0 * y + yaw + 100.0) << node;
      EXPECT_EQ(status[node], node == 5 ? 2 : 0) << node;
      ++node;
    }
  }
  EXPECT_EQ(wrc_table_node_values(nullptr), nullptr);
  EXPECT_EQ(wrc_table_node_status(nullptr), nullptr);
}

}  // namespace
