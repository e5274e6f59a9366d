// The FMU's start values (fmu/start_values.h) and its variable list (fmu/variables.h): what the
// binary reads is what `wrc fmu` wrote, and a damaged file is refused by line.

#include <gtest/gtest.h>

#include <cmath>
#include <set>
#include <stdexcept>
#include <string>

#include "fmu/model_description.h"
#include "fmu/start_values.h"
#include "fmu/variables.h"

namespace {

using namespace wrc::fmu;  // NOLINT

TEST(FmuVariables, AreIndexedByValueReferenceWithUniqueNames) {
  const auto& variables = Variables();
  ASSERT_EQ(variables.size(), kNumVariables);
  std::set<std::string> names;
  for (std::uint32_t i = 0; i < kNumVariables; ++i) {
    EXPECT_EQ(variables[i].value_reference, i);
    EXPECT_TRUE(names.insert(variables[i].name).second) << variables[i].name;
  }
  EXPECT_EQ(variables[kRightFx + kFlagsOffset].name, "right.flags");
  EXPECT_EQ(variables[kVelocity].name, "velocity");
  EXPECT_EQ(variables[kWheelsetFx + 5].name, "wheelset.mz");
}

TEST(FmuStartValues, RoundTripEveryNumberAndString) {
  StartValues values;
  values[kRightTable] = "tables/my right table.wrct";
  values[kVelocity] = StartNumber(0.1 + 0.2);
  values[kLeftMu] = StartNumber(NAN);
  values[kInterpolation] = "2";
  const StartValues back = ParseStartValues(FormatStartValues(values));
  EXPECT_EQ(back, values);
  EXPECT_EQ(std::stod(back.at(kVelocity)), 0.1 + 0.2);  // %.17g round-trips
  EXPECT_TRUE(std::isnan(std::stod(back.at(kLeftMu))));
}

TEST(FmuStartValues, RefuseADamagedFileNamingTheLine) {
  const auto message = [](const std::string& text) {
    try {
      ParseStartValues(text);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_EQ(message("# c\nvelocity = 2\nwheelset.fy = 1\n"),
            "line 3: \"wheelset.fy\" is not a parameter or input of the FMU");
  EXPECT_EQ(message("velocity 2\n"), "line 1 has no \" = \"");
  EXPECT_EQ(message("velocity = 2 m/s\n"), "line 1: \"2 m/s\" is not a valid value of velocity");
  EXPECT_EQ(message("interpolation = 1.5\n"),
            "line 1: \"1.5\" is not a valid value of interpolation");
  EXPECT_EQ(message("y = 0\ny = 1\n"), "line 2: y is given twice");
}

TEST(FmuModelDescription, EscapesWhatXmlCannotHoldLiterally) {
  EXPECT_EQ(XmlEscape("a<b & \"c\" 'd'>\x01"), "a&lt;b &amp; &quot;c&quot; &apos;d&apos;&gt; ");
  StartValues start;
  start[kRightTable] = "a&b.wrct";
  const std::string xml =
      ModelDescriptionXml(start, {"table <x>", "wrc test", "2026-01-01T00:00:00Z"});
  EXPECT_NE(xml.find("<Start value=\"a&amp;b.wrct\"/>"), std::string::npos);
  EXPECT_NE(xml.find("description=\"table &lt;x&gt;\""), std::string::npos);
  EXPECT_NE(xml.find(std::string("instantiationToken=\"") + kInstantiationToken),
            std::string::npos);
}

}  // namespace
