#pragma once
// Table-driven checklist tests: checklist items that share one body are rows of one TEST_P, each
// row named after its item (`.name = "CE_05_VpBelowVs"`, the item id first), so that
// `ctest -R CE_05` finds it and tests/checklist/named_items.sh counts it.
//
//   INSTANTIATE_TEST_SUITE_P(Items, Refusal3602, ::testing::ValuesIn(kRefusals), RowName{});
#include <gtest/gtest.h>

#include <string>

namespace stepmod::testing {

// gtest's name of a row: the row's `name`.
struct RowName {
  template <class Row>
  std::string operator()(const ::testing::TestParamInfo<Row>& info) const {
    return info.param.name;
  }
};

}  // namespace stepmod::testing
