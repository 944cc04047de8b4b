// core::SectionReader / SectionPrinter / Range: the one way a module's settings section is
// read (file over defaults, range-checked, errors naming file and key) and printed back.
#include <gtest/gtest.h>

#include "error_of.h"
#include "lumaslam/core/error.h"
#include "lumaslam/core/settings_section.h"

namespace lumaslam::core {
namespace {

struct Demo {
  int count = 3;
  double fraction = 0.5;
  float radius = 7.0F;
  bool enabled = true;
  std::size_t capacity = 16;
};

template <typename Keys>
void visitDemoKeys(Keys& keys, Demo& d) {
  keys("count", d.count, Range::atLeast(1));
  keys("fraction", d.fraction, Range::between(0.0, 1.0));
  keys("radius", d.radius, Range::above(0.0));
  keys("enabled", d.enabled);
  keys("capacity", d.capacity, Range::atLeast(1));
}

Demo read(const std::string& yaml) {
  const auto file = SettingsFile::fromString("%YAML:1.0\n" + yaml, "demo.yaml");
  Demo d;
  const SectionReader reader(file, "Demo");
  visitDemoKeys(reader, d);
  return d;
}

std::string print(Demo d) {
  SectionPrinter printer("Demo");
  visitDemoKeys(printer, d);
  return printer.text();
}

TEST(CoreSettingsSection, AbsentKeysKeepTheDefaults) {
  const Demo d = read("Other.count: 9\n");
  EXPECT_EQ(d.count, 3);
  EXPECT_EQ(d.fraction, 0.5);
  EXPECT_TRUE(d.enabled);
  EXPECT_EQ(d.capacity, 16U);
}

TEST(CoreSettingsSection, PresentKeysAreRead) {
  const Demo d = read(
      "Demo.count: 9\nDemo.fraction: 0.25\nDemo.radius: 2.5\nDemo.enabled: 0\n"
      "Demo.capacity: 4\n");
  EXPECT_EQ(d.count, 9);
  EXPECT_EQ(d.fraction, 0.25);
  EXPECT_EQ(d.radius, 2.5F);
  EXPECT_FALSE(d.enabled);
  EXPECT_EQ(d.capacity, 4U);
}

TEST(CoreSettingsSection, OutOfRangeValuesAreErrorsNamingFileKeyAndRange) {
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"Demo.count: 0\n", "demo.yaml: key 'Demo.count': must be >= 1, found 0"},
      {"Demo.fraction: 1.01\n", "key 'Demo.fraction': must be in [0, 1], found 1.01"},
      {"Demo.radius: 0\n", "key 'Demo.radius': must be > 0, found 0"},
      {"Demo.capacity: -3\n", "key 'Demo.capacity': must be >= 1, found -3"},
  };
  for (const auto& [yaml, message] : cases) {
    const std::string what = test::errorOf([&] { (void)read(yaml); });
    EXPECT_NE(what.find(message), std::string::npos) << "for " << yaml << ": " << what;
  }
}

TEST(CoreSettingsSection, PrintedLinesReadBackToTheSameValues) {
  Demo d;
  d.count = 12;
  d.fraction = 1.0 / 3.0;
  d.radius = 7.3F;
  d.enabled = false;
  d.capacity = 5;
  const std::string text = print(d);
  EXPECT_EQ(text,
            "Demo.count: 12\nDemo.fraction: 0.3333333333333333\nDemo.radius: 7.3\n"
            "Demo.enabled: false\nDemo.capacity: 5\n");
  const Demo back = read(text);
  EXPECT_EQ(back.count, d.count);
  EXPECT_EQ(back.fraction, d.fraction);  // every digit: bit-identical
  EXPECT_EQ(back.radius, d.radius);
  EXPECT_EQ(back.enabled, d.enabled);
  EXPECT_EQ(back.capacity, d.capacity);
  EXPECT_EQ(print(back), text);
}

TEST(CoreSettingsSection, WholeRealsArePrintedAsReals) {
  Demo d;
  d.fraction = 1.0;
  d.radius = 8.0F;
  const std::string text = print(d);
  EXPECT_NE(text.find("Demo.fraction: 1.0\n"), std::string::npos) << text;
  EXPECT_NE(text.find("Demo.radius: 8.0\n"), std::string::npos) << text;
}

TEST(CoreSettingsSection, RangeDescriptions) {
  EXPECT_EQ(Range::atLeast(1).describe(), ">= 1");
  EXPECT_EQ(Range::above(0).describe(), "> 0");
  EXPECT_EQ(Range::between(0, 1).describe(), "in [0, 1]");
  EXPECT_EQ((Range{0.0, 1.0, false}).describe(), "in (0, 1]");
  EXPECT_TRUE(Range::any().contains(-1e300));
  EXPECT_FALSE(Range::above(0).contains(0.0));
}

// Text keys (Detector.type, Detector.model) go through the same reader and printer, quoted.
TEST(CoreSettingsSection, TextKeysReadBackQuoted) {
  std::string type = "yolo";
  SectionPrinter printer("Demo");
  printer("type", std::string("box_file"));
  EXPECT_EQ(printer.text(), "Demo.type: \"box_file\"\n");
  const auto file = SettingsFile::fromString("%YAML:1.0\n" + printer.text(), "demo.yaml");
  SectionReader(file, "Demo")("type", type);
  EXPECT_EQ(type, "box_file");
}

// Log-odds thresholds (Dynamic.dynamicBelow) have a negative range.
TEST(CoreSettingsSection, NegativeRanges) {
  const Range below = Range::between(-20.0, 0.0);
  EXPECT_EQ(below.describe(), "in [-20, 0]");
  EXPECT_TRUE(below.contains(-2.0));
  EXPECT_FALSE(below.contains(0.5));
}

}  // namespace
}  // namespace lumaslam::core
